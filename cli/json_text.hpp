#pragma once
// The text of a JSON document the CLI writes (adev, psd, fit, check --format json, analyze's
// results.json): a string that is not UTF-8 (a file name from another system) is written with
// U+FFFD for each invalid byte instead of ending the run in nlohmann's type_error.316, as the
// library's own documents are (lib/src/json_text.hpp).
#include <nlohmann/json.hpp>

#include <string>

namespace sigmatau::cli {

/// doc.dump(indent) with invalid UTF-8 replaced by U+FFFD.
inline std::string json_text(const nlohmann::json& doc, int indent) {
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace sigmatau::cli
