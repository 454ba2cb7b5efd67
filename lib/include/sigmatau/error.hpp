#pragma once
/// \file error.hpp
/// Errors a user can fix (bad input data, specs, options) and internal assertions.
/// The CLI maps sigmatau::Error to exit code 2 and prints what() on one line.

#include <cstdint>
#include <stdexcept>
#include <string>

namespace sigmatau {

/// A problem the user can fix: bad input, bad option, bad spec. what() is one actionable line.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// An Error located in a file: what() reads "FILE:LINE:COLUMN: MESSAGE" (line and column are
/// 1-based; 0 means "not applicable" and is left out, e.g. for binary files where `line` is
/// unused and the byte offset goes into the message).
class ParseError : public Error {
 public:
  ParseError(std::string file, std::int64_t line, std::int64_t column, const std::string& message)
      : Error(format(file, line, column, message)),
        file_(std::move(file)),
        line_(line),
        column_(column),
        message_(message) {}

  const std::string& file() const { return file_; }
  std::int64_t line() const { return line_; }
  std::int64_t column() const { return column_; }
  /// The message without the location prefix.
  const std::string& message() const { return message_; }

 private:
  static std::string format(const std::string& file, std::int64_t line, std::int64_t column,
                            const std::string& message) {
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string s = file;
    if (line > 0) {
      s += ':';
      s += std::to_string(line);
      if (column > 0) {
        s += ':';
        s += std::to_string(column);
      }
    }
    s += ": ";
    s += message;
    return s;
  }
  std::string file_;
  std::int64_t line_;
  std::int64_t column_;
  std::string message_;
};

}  // namespace sigmatau

/// Internal invariant; compiled out under NDEBUG. Failing it is a bug in sigmatau, not bad input.
#ifdef NDEBUG
#define SIGMATAU_ASSERT(cond, msg) ((void)0)
#else
#define SIGMATAU_ASSERT(cond, msg)                                                        \
  do {                                                                                    \
    if (!(cond))                                                                          \
      throw std::logic_error(std::string("internal error: ") + (msg) + " [" #cond "] at " \
                             __FILE__ ":" + std::to_string(__LINE__));                    \
  } while (0)
#endif
