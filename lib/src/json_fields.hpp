#pragma once
// Private to the library's readers of sigmatau's own JSON documents handed back by a user (a
// saved adev result, a fit / calibrate / analyze result): every number read is checked for its
// type, finiteness and sign, and a bad one named by its field ("FILE: channels[0].parameters.N.
// value: expected a finite number >= 0, got -1"), so that no value is taken silently as absent,
// NaN or negative. Not installed.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace sigmatau::detail {

/// What a number must be.
enum class NumberRule {
  finite,            ///< any finite number
  non_negative,      ///< finite, >= 0
  positive,          ///< finite, > 0
  probability,       ///< in [0, 1]
  confidence_level,  ///< in (0, 1)
};

/// A document's field: its file and its path in the document ("results[0].points[3]"), for
/// messages. `at(key)` and `at(index)` name a member and an element.
struct JsonField {
  std::string file;
  std::string path;

  JsonField at(std::string_view key) const;
  JsonField at(std::size_t index) const;
  /// The same field with a name the user knows it by (a channel's): "channels[0] (gx)".
  JsonField named(std::string_view name) const;
  /// "FILE: PATH: MESSAGE" (a top-level field: "FILE: KEY: MESSAGE").
  std::string message(const std::string& what) const;
};

/// The JSON text of `value`, cut to 40 characters, for messages ("\"abc\"", "-1", "null").
std::string json_shown(const nlohmann::json& value);

/// `parent[key]` as a number obeying `rule`; nothing when `parent` has no `key`, or when it is
/// null and `null_means_absent` (sigmatau writes null for a value it could not compute).
/// Throws Error naming the field otherwise (a string, a bool, null, a negative or out-of-range
/// number).
std::optional<double> optional_number(const nlohmann::json& parent, std::string_view key,
                                      const JsonField& field, NumberRule rule,
                                      bool null_means_absent = false);

/// optional_number, but a missing (or null) `key` is an Error too.
double required_number(const nlohmann::json& parent, std::string_view key, const JsonField& field,
                       NumberRule rule);

/// `parent[key]` as an integer in [low, high]; nothing when absent. Throws Error naming the
/// field when it is not an integer or out of range.
std::optional<std::int64_t> optional_integer(const nlohmann::json& parent, std::string_view key,
                                             const JsonField& field, std::int64_t low,
                                             std::int64_t high);

/// `parent[key]` as text; nothing when absent. Throws Error naming the field when it is not.
std::optional<std::string> optional_text(const nlohmann::json& parent, std::string_view key,
                                         const JsonField& field);

/// One noise term of a fit result's "parameters" (fit_json in analysis_results.cpp: "N": {"value",
/// "ci_low", "ci_high", "edf", "tau_min_s", "unit"} when the fit kept it, {"upper_bound", "unit"}
/// when not), every number checked: value finite and >= 0; ci_low, ci_high and upper_bound the
/// same or null (none could be computed), ci_low <= ci_high; edf and tau_min_s > 0.
struct FitTermFields {
  std::optional<double> value, ci_low, ci_high, upper_bound, tau_min_s;
};

/// The fields of term `key` (N, B, K, Q, R) of `parameters` (at `field`); nothing when absent.
/// Throws Error naming the field for a value of the wrong type, sign or order.
std::optional<FitTermFields> fit_term_fields(const nlohmann::json& parameters, std::string_view key,
                                             const JsonField& field);

}  // namespace sigmatau::detail
