#include "jellysim/fluid/schemes.hpp"

namespace jellysim::fluid {

std::string_view to_string(ConvectionScheme s) {
  switch (s) {
    case ConvectionScheme::donor_cell: return "donor-cell";
    case ConvectionScheme::van_leer: return "van-leer";
    case ConvectionScheme::koren: return "koren";
  }
  return "donor-cell";
}

std::string_view to_string(AdvectionScheme s) {
  switch (s) {
    case AdvectionScheme::linear: return "linear";
    case AdvectionScheme::maccormack: return "maccormack";
    case AdvectionScheme::bfecc: return "bfecc";
    case AdvectionScheme::cubic: return "cubic";
  }
  return "linear";
}

std::optional<ConvectionScheme> convection_scheme_from_string(std::string_view name) {
  for (ConvectionScheme s : {ConvectionScheme::donor_cell, ConvectionScheme::van_leer, ConvectionScheme::koren})
    if (to_string(s) == name) return s;
  return std::nullopt;
}

std::optional<AdvectionScheme> advection_scheme_from_string(std::string_view name) {
  for (AdvectionScheme s :
       {AdvectionScheme::linear, AdvectionScheme::maccormack, AdvectionScheme::bfecc, AdvectionScheme::cubic})
    if (to_string(s) == name) return s;
  return std::nullopt;
}

const std::vector<std::string>& convection_scheme_names() {
  static const std::vector<std::string> names{"donor-cell", "van-leer", "koren"};
  return names;
}

const std::vector<std::string>& advection_scheme_names() {
  static const std::vector<std::string> names{"linear", "maccormack", "bfecc", "cubic"};
  return names;
}

}  // namespace jellysim::fluid
