// Checked numbers and texts of the JSON documents sigmatau reads back (json_fields.hpp).
#include "json_fields.hpp"

#include <cmath>
#include <limits>

#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// What `rule` asks for, as said in a message.
std::string_view expected(NumberRule rule) {
  switch (rule) {
    case NumberRule::finite:
      return "a finite number";
    case NumberRule::non_negative:
      return "a finite number >= 0";
    case NumberRule::positive:
      return "a finite number > 0";
    case NumberRule::probability:
      return "a number in [0, 1]";
    case NumberRule::confidence_level:
      return "a number in (0, 1)";
  }
  return "a number";
}

bool obeys(double v, NumberRule rule) {
  switch (rule) {
    case NumberRule::finite:
      return std::isfinite(v);
    case NumberRule::non_negative:
      return std::isfinite(v) && v >= 0;
    case NumberRule::positive:
      return std::isfinite(v) && v > 0;
    case NumberRule::probability:
      return v >= 0 && v <= 1;
    case NumberRule::confidence_level:
      return v > 0 && v < 1;
  }
  return false;
}

/// Characters of a shown value before it is cut.
constexpr std::size_t kShownLength = 40;

}  // namespace

JsonField JsonField::at(std::string_view key) const {
  return {file, path.empty() ? std::string(key) : path + "." + std::string(key)};
}

JsonField JsonField::at(std::size_t index) const {
  return {file, path + "[" + std::to_string(index) + "]"};
}

JsonField JsonField::named(std::string_view name) const {
  return name.empty() ? *this : JsonField{file, path + " (" + std::string(name) + ")"};
}

std::string JsonField::message(const std::string& what) const {
  return file + ": " + (path.empty() ? "" : path + ": ") + what;
}

std::string json_shown(const nlohmann::json& value) {
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kShownLength) text = text.substr(0, kShownLength) + "...";
  return text;
}

std::optional<double> optional_number(const nlohmann::json& parent, std::string_view key,
                                      const JsonField& field, NumberRule rule,
                                      bool null_means_absent) {
  if (!parent.is_object()) return std::nullopt;
  const auto it = parent.find(key);
  if (it == parent.end()) return std::nullopt;
  if (it->is_null() && null_means_absent) return std::nullopt;
  const JsonField here = field.at(key);
  // A number too large for a double (1e999) reads as infinite: not finite, refused below.
  const double v = it->is_number() ? it->get<double>() : std::numeric_limits<double>::quiet_NaN();
  if (!it->is_number() || !obeys(v, rule)) {
    throw Error(
        here.message("expected " + std::string(expected(rule)) + ", got " + json_shown(*it)));
  }
  return v;
}

double required_number(const nlohmann::json& parent, std::string_view key, const JsonField& field,
                       NumberRule rule) {
  const std::optional<double> v = optional_number(parent, key, field, rule);
  if (!v) {
    throw Error(field.at(key).message("missing; expected " + std::string(expected(rule))));
  }
  return *v;
}

std::optional<std::int64_t> optional_integer(const nlohmann::json& parent, std::string_view key,
                                             const JsonField& field, std::int64_t low,
                                             std::int64_t high) {
  if (!parent.is_object()) return std::nullopt;
  const auto it = parent.find(key);
  if (it == parent.end()) return std::nullopt;
  bool in_range = false;
  if (it->is_number_unsigned()) {  // JSON reads a non-negative integer as unsigned
    const auto u = it->get<std::uint64_t>();
    in_range = high >= 0 && u <= static_cast<std::uint64_t>(high) &&
               (low <= 0 || u >= static_cast<std::uint64_t>(low));
  } else if (it->is_number_integer()) {
    const auto i = it->get<std::int64_t>();
    in_range = i >= low && i <= high;
  }
  if (!in_range) {
    throw Error(field.at(key).message("expected an integer in [" + std::to_string(low) + ", " +
                                      std::to_string(high) + "], got " + json_shown(*it)));
  }
  return it->get<std::int64_t>();
}

std::optional<std::string> optional_text(const nlohmann::json& parent, std::string_view key,
                                         const JsonField& field) {
  if (!parent.is_object()) return std::nullopt;
  const auto it = parent.find(key);
  if (it == parent.end()) return std::nullopt;
  if (!it->is_string()) {
    throw Error(field.at(key).message("expected a text, got " + json_shown(*it)));
  }
  return it->get<std::string>();
}

std::optional<FitTermFields> fit_term_fields(const nlohmann::json& parameters, std::string_view key,
                                             const JsonField& field) {
  if (!parameters.is_object()) {
    throw Error(field.message("expected an object of noise terms, got " + json_shown(parameters)));
  }
  const auto it = parameters.find(key);
  if (it == parameters.end()) return std::nullopt;
  const JsonField term = field.at(key);
  if (!it->is_object()) throw Error(term.message("expected an object, got " + json_shown(*it)));
  FitTermFields out;
  out.value = optional_number(*it, "value", term, NumberRule::non_negative);
  out.ci_low = optional_number(*it, "ci_low", term, NumberRule::non_negative, true);
  out.ci_high = optional_number(*it, "ci_high", term, NumberRule::non_negative, true);
  out.upper_bound = optional_number(*it, "upper_bound", term, NumberRule::non_negative, true);
  out.tau_min_s = optional_number(*it, "tau_min_s", term, NumberRule::positive);
  optional_number(*it, "edf", term, NumberRule::positive);
  optional_text(*it, "unit", term);
  if (out.ci_low && out.ci_high && !(*out.ci_low <= *out.ci_high)) {
    throw Error(term.message("expected ci_low <= ci_high, got " + json_shown((*it)["ci_low"]) +
                             " > " + json_shown((*it)["ci_high"])));
  }
  return out;
}

}  // namespace sigmatau::detail
