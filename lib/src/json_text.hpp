#pragma once
// Internal: the text of a JSON document, for every place the library writes one (results.json,
// the filter JSON, simulate's truth, calibrate's and compliance's documents). A string that is
// not UTF-8 (a file name from another system, a name in a corrupt bag) must not end the run in
// nlohmann's type_error.316: each invalid byte is written as U+FFFD instead. Names read from a
// log are already UTF-8 (text_encoding.hpp); this is the guard for everything else.
#include <nlohmann/json.hpp>

#include <string>

namespace sigmatau::detail {

/// doc.dump(indent) with invalid UTF-8 replaced by U+FFFD (-1: compact).
inline std::string json_text(const nlohmann::json& doc, int indent = -1) {
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace sigmatau::detail
