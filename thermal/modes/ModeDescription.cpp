#include "thermal/modes/ModeDescription.h"

#include <charconv>
#include <stdexcept>

namespace tmdem::thermal {

std::string parameter_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

bool ParameterRange::contains(double v) const {
  switch (kind) {
    case Kind::Any: return true;
    case Kind::Greater: return v > lo;
    case Kind::AtLeast: return v >= lo;
    case Kind::Open: return v > lo && v < hi;
    case Kind::OpenClosed: return v > lo && v <= hi;
    case Kind::Closed: return v >= lo && v <= hi;
  }
  return true;
}

std::string ParameterRange::interval() const {
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here.
  std::string out;
  const auto pair = [&](char open, char close) {
    out += open;
    out += parameter_text(lo);
    out += ", ";
    out += parameter_text(hi);
    out += close;
  };
  switch (kind) {
    case Kind::Any: out = "any finite number"; break;
    case Kind::Greater: out = "> "; out += parameter_text(lo); break;
    case Kind::AtLeast: out = ">= "; out += parameter_text(lo); break;
    case Kind::Open: pair('(', ')'); break;
    case Kind::OpenClosed: pair('(', ']'); break;
    case Kind::Closed: pair('[', ']'); break;
  }
  return out;
}

std::string ParameterRange::describe() const {
  if (kind == Kind::Any) return "must be a finite number";
  std::string out = kind == Kind::Greater || kind == Kind::AtLeast ? "must be " : "must be in ";
  out += interval();
  return out;
}

ModeParameters::ModeParameters(const ModeDescription& mode, std::vector<double> values)
    : mode_(&mode), values_(std::move(values)) {
  if (values_.size() != mode.parameters.size())
    throw std::logic_error("mode " + std::string(mode.name) + ": " +
                           std::to_string(values_.size()) + " values for " +
                           std::to_string(mode.parameters.size()) + " parameters");
}

double ModeParameters::operator[](std::string_view key) const {
  for (std::size_t i = 0; i < mode_->parameters.size(); ++i)
    if (mode_->parameters[i].key == key) return values_[i];
  throw std::logic_error("mode " + std::string(mode_->name) + " declares no parameter " +
                         std::string(key));
}

std::string_view ModeParameters::choice(std::string_view key) const {
  for (std::size_t i = 0; i < mode_->parameters.size(); ++i)
    if (mode_->parameters[i].key == key) {
      const auto& names = mode_->parameters[i].choices;
      const auto index = std::size_t(values_[i]);
      if (names.empty() || index >= names.size())
        throw std::logic_error("mode " + std::string(mode_->name) + ": " + std::string(key) +
                               " is not a choice parameter with a valid index");
      return names[index];
    }
  throw std::logic_error("mode " + std::string(mode_->name) + " declares no parameter " +
                         std::string(key));
}

}  // namespace tmdem::thermal
