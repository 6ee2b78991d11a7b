#pragma once
// Line and field handling shared by the text particle readers (CSV, LAMMPS dump): each field
// keeps its 1-based character column, so an error names FILE:LINE:COLUMN and the column's
// header name.
#include <string>
#include <string_view>
#include <vector>

namespace tmdem::coupling {

struct TextField {
  std::string_view text;  // trimmed of spaces and tabs
  long long column = 0;   // 1-based character column of its first character
};

// The lines of `text` (without their "\n" or "\r\n").
std::vector<std::string_view> split_lines(std::string_view text);

// Fields separated by `separator`; separator ' ' splits on runs of spaces and tabs.
std::vector<TextField> split_fields(std::string_view line, char separator);

// Reads one value of the named column at `line`; PackingFileError naming FILE:LINE:COLUMN, the
// column and the text otherwise. Numbers must be finite and use the whole field.
class FieldReader {
 public:
  FieldReader(const std::string& file, long long line) : file_(file), line_(line) {}
  double number(const TextField& field, std::string_view column_name) const;
  long long integer(const TextField& field, std::string_view column_name) const;
  bool boolean(const TextField& field, std::string_view column_name) const;  // 0/1/true/false

 private:
  [[noreturn]] void fail(const TextField& field, std::string_view column_name,
                         std::string_view expected) const;
  const std::string& file_;
  long long line_;
};

}  // namespace tmdem::coupling
