#pragma once
// Reading the plan files of `jellysim batch` and `jellysim optimize` (private to experiments):
// dotted keys in file order, values as the TOML text of a --set value, and the shared [set] table.
#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

namespace jellysim::experiments {

/// A value of a plan with its dotted key and where it stands in the file (plan order).
struct PlanLeaf {
  std::string key;
  const toml::node* node;
  toml::source_position at;
};

/// The values of a table with dotted keys ("a.b" = …, a.b = … and [x.a] b = … are the same key),
/// in the order of the file.
std::vector<PlanLeaf> plan_leaves(const toml::table& table, const std::string& prefix = "");
/// A plan value as the TOML text of a --set value; `where` names it in errors.
std::string plan_literal(const toml::node& n, const std::string& where);
/// A plan file's text parsed as TOML; a syntax error is an InputError naming `file` and the line.
toml::table parse_plan_toml(std::string_view text, const std::string& file);
/// [set]: key=value assignments for every run, in plan order (`scene` refused). `file` names it.
std::vector<std::string> read_plan_set(const toml::node& node, const std::string& file);

}  // namespace jellysim::experiments
