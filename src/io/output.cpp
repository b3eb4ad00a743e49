#include "jellysim/io/output.hpp"

#include "jellysim/core/errors.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace jellysim::io {

OutputDir::OutputDir(std::filesystem::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_)) {
    throw RunError("cannot create output directory '" + dir_.string() + "': " + ec.message());
  }
}

std::filesystem::path OutputDir::temporary_for(std::string_view name) const {
  // The process id keeps two concurrent writers of the same directory apart.
  return dir_ / (std::string(name) + ".tmp-" + std::to_string(::getpid()));
}

void OutputDir::commit(const std::filesystem::path& temporary, std::string_view name) const {
  std::error_code ec;
  std::filesystem::rename(temporary, dir_ / name, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw RunError("cannot write '" + (dir_ / name).string() + "': " + ec.message());
  }
}

void OutputDir::write_text(std::string_view name, std::string_view content) const {
  const auto tmp = temporary_for(name);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw RunError("cannot write '" + (dir_ / name).string() + "'");
    }
  }
  commit(tmp, name);
}

void OutputDir::write_json(std::string_view name, const nlohmann::ordered_json& json) const {
  write_text(name, json.dump(2) + "\n");
}

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

CsvWriter::CsvWriter(const std::vector<std::string>& columns) : columns_(columns.size()) {
  for (std::size_t i = 0; i < columns.size(); ++i) text_ += (i ? "," : "") + columns[i];
  text_ += '\n';
}

void CsvWriter::append_number(double v) { text_ += format_double(v); }

void CsvWriter::row(std::initializer_list<double> values) {
  if (values.size() != columns_) throw std::logic_error("CSV row has the wrong number of cells");
  bool first = true;
  for (double v : values) {
    if (!first) text_ += ',';
    append_number(v);
    first = false;
  }
  text_ += '\n';
  ++rows_;
}

void CsvWriter::row(std::initializer_list<std::string_view> labels, std::initializer_list<double> values) {
  if (labels.size() + values.size() != columns_) throw std::logic_error("CSV row has the wrong number of cells");
  bool first = true;
  for (std::string_view label : labels) {
    if (!first) text_ += ',';
    text_ += label;
    first = false;
  }
  for (double v : values) {
    text_ += ',';
    append_number(v);
  }
  text_ += '\n';
  ++rows_;
}

}  // namespace jellysim::io
