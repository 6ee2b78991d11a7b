#include "coupling/scene/TomlWriter.h"
#include "coupling/common/ShortestNumber.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string_view>

namespace tmdem::coupling {

namespace {

bool is_bare_key(std::string_view key) {
  if (key.empty()) return false;
  for (const char c : key)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  return true;
}

}  // namespace

std::string toml_basic_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(c));
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

namespace {

std::string key_text(std::string_view key) {
  return is_bare_key(key) ? std::string(key) : toml_basic_string(key);
}

std::string float_text(double value) {
  std::string text = shortest_number(value);
  // TOML needs a '.' or an exponent to read the number back as a float.
  if (std::isfinite(value) && text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

void write_inline(std::ostream& out, const toml::node& node);

void write_inline_table(std::ostream& out, const toml::table& table) {
  if (table.empty()) {
    out << "{}";
    return;
  }
  out << "{ ";
  bool first = true;
  for (const auto& [key, value] : table) {
    if (!first) out << ", ";
    first = false;
    out << key_text(key.str()) << " = ";
    write_inline(out, value);
  }
  out << " }";
}

void write_inline(std::ostream& out, const toml::node& node) {
  if (const auto* s = node.as_string()) {
    out << toml_basic_string(s->get());
  } else if (const auto* i = node.as_integer()) {
    out << i->get();
  } else if (const auto* f = node.as_floating_point()) {
    out << float_text(f->get());
  } else if (const auto* b = node.as_boolean()) {
    out << (b->get() ? "true" : "false");
  } else if (const auto* a = node.as_array()) {
    out << "[";
    for (std::size_t k = 0; k < a->size(); ++k) {
      out << (k == 0 ? "" : ", ");
      write_inline(out, *a->get(k));
    }
    out << "]";
  } else if (const auto* t = node.as_table()) {
    write_inline_table(out, *t);
  } else if (const auto* d = node.as_date()) {
    out << *d;  // dates and times: toml++'s own form
  } else if (const auto* t = node.as_time()) {
    out << *t;
  } else if (const auto* dt = node.as_date_time()) {
    out << *dt;
  }
}

bool is_array_of_tables(const toml::node& node) {
  const auto* array = node.as_array();
  return array != nullptr && !array->empty() && array->is_array_of_tables();
}

// Writes the plain values of `table`, then its sub-tables and arrays of tables under `prefix`.
void write_table(std::ostream& out, const toml::table& table, const std::string& prefix,
                 bool& wrote_something) {
  for (const auto& [key, value] : table) {
    if (value.is_table() || is_array_of_tables(value)) continue;
    out << key_text(key.str()) << " = ";
    write_inline(out, value);
    out << "\n";
    wrote_something = true;
  }
  for (const auto& [key, value] : table) {
    const std::string name = prefix.empty() ? key_text(key.str()) : prefix + "." + key_text(key.str());
    if (const auto* sub = value.as_table()) {
      out << (wrote_something ? "\n" : "") << "[" << name << "]\n";
      wrote_something = true;
      write_table(out, *sub, name, wrote_something);
    } else if (is_array_of_tables(value)) {
      for (const auto& element : *value.as_array()) {
        out << (wrote_something ? "\n" : "") << "[[" << name << "]]\n";
        wrote_something = true;
        for (const auto& [k, v] : *element.as_table()) {
          out << key_text(k.str()) << " = ";
          write_inline(out, v);
          out << "\n";
        }
      }
    }
  }
}

}  // namespace

std::string write_toml(const toml::table& root) {
  std::ostringstream out;
  bool wrote_something = false;
  write_table(out, root, "", wrote_something);
  return out.str();
}

std::string write_toml_value(const toml::node& value) {
  std::ostringstream out;
  write_inline(out, value);
  return out.str();
}

}  // namespace tmdem::coupling
