#include "coupling/scene/PackingText.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "coupling/scene/PackingFile.h"

namespace tmdem::coupling {

std::string read_packing_text(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw PackingFileError(path, 0, 0, "no such file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw PackingFileError(path, 0, 0, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PackingFileError(path, 0, 0, "cannot open the file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw PackingFileError(path, 0, 0, "cannot read the file");
  return text.str();
}

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    begin = end + 1;
  }
  return lines;
}

std::vector<TextField> split_fields(std::string_view line, char separator) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  std::vector<TextField> fields;
  std::size_t i = 0;
  if (separator == ' ') {
    while (i < line.size()) {
      while (i < line.size() && blank(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !blank(line[i])) ++i;
      fields.push_back({line.substr(start, i - start), static_cast<long long>(start) + 1});
    }
    return fields;
  }
  while (true) {
    std::size_t end = line.find(separator, i);
    if (end == std::string_view::npos) end = line.size();
    std::size_t a = i, b = end;
    while (a < b && blank(line[a])) ++a;
    while (b > a && blank(line[b - 1])) --b;
    fields.push_back({line.substr(a, b - a), static_cast<long long>(a) + 1});
    if (end == line.size()) break;
    i = end + 1;
  }
  return fields;
}

void FieldReader::fail(const TextField& field, std::string_view column_name,
                       std::string_view expected) const {
  throw PackingFileError(file_, line_, field.column,
                         "column " + std::string(column_name) + ": expected " +
                             std::string(expected) + ", got \"" + std::string(field.text) + "\"");
}

double FieldReader::number(const TextField& field, std::string_view column_name) const {
  std::string_view text = field.text;
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value))
    fail(field, column_name, "a finite number");
  return value;
}

long long FieldReader::integer(const TextField& field, std::string_view column_name) const {
  long long value = 0;
  const auto& text = field.text;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    fail(field, column_name, "an integer");
  return value;
}

bool FieldReader::boolean(const TextField& field, std::string_view column_name) const {
  if (field.text == "1" || field.text == "true") return true;
  if (field.text == "0" || field.text == "false") return false;
  fail(field, column_name, "0, 1, true or false");
}

}  // namespace tmdem::coupling
