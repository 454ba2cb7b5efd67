// Internal: text log parser. One buffer of `block_bytes_` is read at a time; a line cut by the
// end of the buffer is moved to the front before the next read, so memory stays at one buffer
// plus one line (kMaxLineBytes). Numbers are parsed in place with std::from_chars; the slow path
// (spaces, quotes, '+', errors) runs only for fields the fast path rejects.
#include "text_log.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

const char* find_char(const char* b, const char* e, char c) {
  const void* hit = std::memchr(b, c, static_cast<std::size_t>(e - b));
  return hit ? static_cast<const char*>(hit) : e;
}
const char* skip_blanks(const char* b, const char* e) {
  while (b != e && is_blank(*b)) ++b;
  return b;
}
const char* find_blank(const char* b, const char* e) {
  while (b != e && !is_blank(*b)) ++b;
  return b;
}

/// The delimiter rule (see log_reader.hpp): tab, else comma, else runs of blanks (0).
char detect_delimiter(const char* b, const char* e) {
  if (find_char(b, e, '\t') != e) return '\t';
  if (find_char(b, e, ',') != e) return ',';
  return 0;
}

/// Splits a line by `delimiter` (0: runs of blanks). Throws via `too_many` past kMaxColumns.
template <class TooMany>
std::vector<std::string_view> split_line(const char* b, const char* e, char delimiter,
                                         TooMany too_many) {
  std::vector<std::string_view> fields;
  if (delimiter == 0) {
    for (const char* p = skip_blanks(b, e); p != e; p = skip_blanks(p, e)) {
      const char* q = find_blank(p, e);
      fields.emplace_back(p, static_cast<std::size_t>(q - p));
      if (fields.size() > kMaxColumns) too_many();
      p = q;
    }
    return fields;
  }
  for (const char* p = b;;) {
    const char* q = find_char(p, e, delimiter);
    fields.emplace_back(p, static_cast<std::size_t>(q - p));
    if (fields.size() > kMaxColumns) too_many();
    if (q == e) break;
    p = q + 1;
  }
  return fields;
}

std::size_t count_fields(const char* b, const char* e, char delimiter) {
  if (delimiter != 0) return 1 + static_cast<std::size_t>(std::count(b, e, delimiter));
  std::size_t n = 0;
  for (const char* p = skip_blanks(b, e); p != e; p = skip_blanks(p, e)) {
    p = find_blank(p, e);
    ++n;
  }
  return n;
}

}  // namespace

TextLog::TextLog(ByteSource& source, const LogOptions& options, std::size_t block_bytes,
                 TimingAccumulator& timing)
    : source_(source),
      timing_(timing),
      nonfinite_(options.nonfinite),
      block_bytes_(block_bytes),
      buffer_(block_bytes + kMaxLineBytes + 1) {
  timing_.set_policy(options.gaps, source_.name());
  begin_ = end_ = buffer_.data();
  while (!eof_ && end_ - begin_ < 3) refill();
  // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first field.
  if (end_ - begin_ >= 3 && std::memcmp(begin_, "\xEF\xBB\xBF", 3) == 0) begin_ += 3;

  const auto too_many = [&] {
    fail(line_, 0,
         "more than " + std::to_string(kMaxColumns) + " columns (the limit; is this a text log?)");
  };
  const auto no_rows = [&](const std::string& why) { fail(0, 0, "no data rows: " + why); };
  const auto check_text = [&](const char* b, const char* e) {
    if (std::memchr(b, '\0', static_cast<std::size_t>(e - b))) {
      fail(line_, 0,
           "binary data (a NUL byte) in a text log; raw binary samples need a binary format "
           "(--binary) and a channel count");
    }
  };

  const char* b = nullptr;
  const char* e = nullptr;
  // Comments and a preamble of "Key: value" lines before the first row; a Stable32 data file
  // declares its Type and Tau there.
  TextHeader notes;
  bool found = false;
  while (!found && next_line(b, e)) {
    if (e != b && e[-1] == '\r') --e;
    const char* p = skip_blanks(b, e);
    if (p == e) continue;
    const bool comment = *p == '#' || *p == '%';
    if (comment || is_preamble_line(p, e)) {
      read_declaration(comment ? p + 1 : p, e, notes);
      continue;
    }
    found = true;
  }
  if (!found) no_rows("the input is empty or holds only comments");
  check_text(b, e);
  // Header rule: a first row with any field that is not a number, split by its own delimiter.
  bool header = false;
  for (const auto f : split_line(b, e, detect_delimiter(b, e), too_many)) {
    if (!to_number(f)) header = true;
  }
  std::string header_text;
  std::int64_t header_line = 0;
  if (header) {
    header_text.assign(b, e);
    header_line = line_;
    if (!next_content_line(b, e)) {
      no_rows("only a header (line " + std::to_string(header_line) + ")");
    }
    check_text(b, e);
  }
  const char* first_row = b;
  const char* const first_row_end = e;
  // The delimiter comes from the first data line.
  delimiter_ = detect_delimiter(b, e);
  mode_ = delimiter_ == 0 ? Mode::whitespace : Mode::delimited;
  const auto data = split_line(b, e, delimiter_, too_many);
  std::vector<std::string> names;
  if (header) {
    if (data.size() == 1) {
      names.emplace_back(trim_field(header_text));  // one column: the whole line is its name
    } else {
      const char* hb = header_text.data();
      for (const auto f : split_line(hb, hb + header_text.size(), delimiter_, too_many)) {
        names.emplace_back(trim_field(f));
      }
    }
    fields_ = names.size();
    if (data.size() != fields_) fail_ragged(first_row, first_row_end);
  } else {
    fields_ = data.size();
    names.assign(fields_, std::string());
  }
  std::vector<bool> numeric(fields_);
  for (std::size_t c = 0; c < fields_; ++c) numeric[c] = to_number(data[c]).has_value();
  // "0;0.1" under a comma header (or none) is one field that is no number: say why ("no
  // numeric columns" gives the hint for a ';' header itself).
  if (std::none_of(numeric.begin(), numeric.end(), [](bool n) { return n; }) &&
      header_text.find(';') == std::string::npos &&
      std::find(first_row, first_row_end, ';') != first_row_end) {
    fail(line_, 0, "the first data row holds no number" + semicolon_hint("it"));
  }
  const auto label = [&](std::size_t c) {
    return header && !names[c].empty() ? shown_name(names[c]) : unnamed_column(c);
  };
  // Columns whose first data field is not a number (read by default only when numeric): a
  // number with a decimal comma is an error; a column that holds numbers in most of the rows
  // after it is data whose first field is wrong (an error when that row is parsed, or the row
  // skipped under NonFinitePolicy::skip_row); the others are text, left out and listed.
  std::vector<std::size_t> doubtful;
  std::vector<std::string> first_fields;
  if (options.columns.empty()) {
    for (std::size_t c = 0; c < fields_; ++c) {
      if (numeric[c]) continue;
      const std::string_view field = trim_field(data[c]);
      if (has_decimal_comma(field)) fail_decimal_comma(line_, c, field, label(c));
      doubtful.push_back(c);
      first_fields.emplace_back(field.substr(0, kMaxQuotedField));
    }
  }
  const std::int64_t first_line = line_;
  // From here the first data row is re-read by read_rows: rewind to it (nothing was read since
  // it was returned), and look ahead from there.
  begin_ = first_row;
  --line_;
  if (!doubtful.empty()) {
    const std::vector<RowCount> counts = numbers_in_rows_ahead(doubtful, label);
    for (std::size_t k = 0; k < doubtful.size(); ++k) {
      const std::size_t c = doubtful[k];
      if (counts[k].rows > 0 && 2 * counts[k].numbers > counts[k].rows) {
        numeric[c] = true;  // data with a bad first field
      } else {
        notes.text_columns.push_back(
            {static_cast<std::int64_t>(c), label(c), first_fields[k], first_line});
      }
    }
  }
  selection_ = select_columns(names, header, numeric, options, source_.name(),
                              header ? header_line : first_line, first_line, "column");
  // Of the columns named as time stamps, the one whose values increase is the time column; the
  // others (a temperature named T) stay channels.
  if (!selection_.time_candidates.empty()) {
    std::vector<int> increasing;
    for (const int c : selection_.time_candidates) {
      if (increases_ahead(static_cast<std::size_t>(c))) {
        increasing.push_back(c);
      } else {
        notes.time_column_not_increasing += (notes.time_column_not_increasing.empty() ? "" : ", ") +
                                            label(static_cast<std::size_t>(c));
      }
    }
    if (increasing.size() > 1) {
      fail(header_line, 0,
           "columns \"" + label(static_cast<std::size_t>(increasing[0])) + "\" and \"" +
               label(static_cast<std::size_t>(increasing[1])) +
               "\" are both named as time stamps: name the time column (time_column)");
    }
    LogOptions chosen = options;
    chosen.find_time_column = false;
    if (increasing.size() == 1) chosen.time_column = std::to_string(increasing.front());
    selection_ = select_columns(names, header, numeric, chosen, source_.name(),
                                header ? header_line : first_line, first_line, "column");
    if (increasing.size() == 1) {
      selection_.time_column_found = label(static_cast<std::size_t>(increasing.front()));
    }
  }
  // A Stable32 data file of two columns is a time tag and the value; Stable32 ignores the tags
  // (its Tau gives the interval), and so does this reader unless a column is named.
  const bool stable32 = !notes.declared_type.empty() || notes.declared_tau_s > 0;
  if (stable32 && fields_ == 2 && options.columns.empty() && !selection_.has_time &&
      numeric[0] && numeric[1]) {
    LogOptions value_only = options;
    value_only.columns = {"1"};
    selection_ = select_columns(names, header, numeric, value_only, source_.name(),
                                header ? header_line : first_line, first_line, "column");
    notes.time_tag_column = label(0);
  }
  std::erase_if(notes.text_columns, [&](const TextColumn& t) {
    return selection_.slots[static_cast<std::size_t>(t.column)] == kTimeColumn;
  });
  notes.time_column_found = selection_.time_column_found;
  notes.time_unit = selection_.time_unit;
  notes.time_unit_from_name = selection_.time_unit_from_name;
  timing_.set_header(std::move(notes));
  row_.assign(selection_.channel_columns.size(), 0.0);
}

bool TextLog::is_preamble_line(const char* b, const char* e) {
  const char* token_end = find_blank(b, e);
  return token_end - b >= 2 && token_end[-1] == ':';
}

void TextLog::read_declaration(const char* b, const char* e, TextHeader& notes) {
  const char* colon = find_char(b, e, ':');
  if (colon == e) return;
  std::string key(trim_field(std::string_view(b, static_cast<std::size_t>(colon - b))));
  std::string value(trim_field(std::string_view(colon + 1, static_cast<std::size_t>(e - colon - 1))));
  for (char& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (char& ch : value) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (key == "type") {
    if (value.rfind("phase", 0) == 0) notes.declared_type = "phase";
    if (value.rfind("freq", 0) == 0) notes.declared_type = "frequency";
  } else if (key == "tau") {
    const auto tau = to_number(value);
    if (tau && *tau > 0 && std::isfinite(*tau)) notes.declared_tau_s = *tau;
  }
}

bool TextLog::has_decimal_comma(std::string_view field) {
  // digits ',' digits, optionally signed and with an exponent: "1,288185", "-0,5e-3".
  std::size_t i = 0;
  if (i < field.size() && (field[i] == '-' || field[i] == '+')) ++i;
  const std::size_t int_start = i;
  while (i < field.size() && field[i] >= '0' && field[i] <= '9') ++i;
  if (i == int_start || i == field.size() || field[i] != ',') return false;
  const std::size_t frac_start = ++i;
  while (i < field.size() && field[i] >= '0' && field[i] <= '9') ++i;
  if (i == frac_start) return false;
  if (i < field.size() && (field[i] == 'e' || field[i] == 'E')) {
    ++i;
    if (i < field.size() && (field[i] == '-' || field[i] == '+')) ++i;
    const std::size_t exp_start = i;
    while (i < field.size() && field[i] >= '0' && field[i] <= '9') ++i;
    if (i == exp_start) return false;
  }
  return i == field.size();
}

void TextLog::fail_decimal_comma(std::int64_t line, std::size_t column, std::string_view field,
                                 const std::string& name) const {
  fail(line, static_cast<std::int64_t>(column + 1),
       "expected a number, found " + quote_field(field) + " in column \"" + name +
           "\": a decimal comma; numbers are read with a decimal point (convert the file's "
           "decimal commas to points)");
}

std::vector<TextLog::RowCount> TextLog::numbers_in_rows_ahead(
    const std::vector<std::size_t>& columns,
    const std::function<std::string(std::size_t)>& label) {
  std::vector<RowCount> counts(columns.size());
  scan_rows_ahead([&](std::int64_t line, const std::vector<std::string_view>& fields) {
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const std::string_view field = trim_field(fields[columns[k]]);
      ++counts[k].rows;
      if (to_number(field)) {
        ++counts[k].numbers;
      } else if (has_decimal_comma(field)) {
        fail_decimal_comma(line, columns[k], field, label(columns[k]));
      }
    }
  });
  return counts;
}

bool TextLog::increases_ahead(std::size_t column) {
  std::int64_t intervals = 0, increasing = 0;
  std::optional<double> previous;
  const auto add = [&](std::string_view field) {
    const auto v = to_number(field);
    if (!v) return;
    if (previous) {
      ++intervals;
      if (*v > *previous) ++increasing;
    }
    previous = v;
  };
  // The first data row (at begin_), then the rows ahead.
  const char* e = static_cast<const char*>(
      std::memchr(begin_, '\n', static_cast<std::size_t>(end_ - begin_)));
  const char* row_end = e ? e : end_;
  if (row_end != begin_ && row_end[-1] == '\r') --row_end;
  add(split_line(begin_, row_end, delimiter_, [] {})[column]);
  scan_rows_ahead([&](std::int64_t, const std::vector<std::string_view>& fields) {
    add(fields[column]);
  });
  return intervals == 0 ||
         static_cast<double>(increasing) >= kIncreasingShare * static_cast<double>(intervals);
}

void TextLog::scan_rows_ahead(
    const std::function<void(std::int64_t, const std::vector<std::string_view>&)>& each) {
  // Best effort within one more read: the rows already in the buffer, topped up once when little
  // is there (a refill keeps everything from begin_, the first data row, on).
  if (!eof_ && static_cast<std::size_t>(end_ - begin_) <= kMaxLineBytes) refill();
  const char* p = static_cast<const char*>(
      std::memchr(begin_, '\n', static_cast<std::size_t>(end_ - begin_)));
  std::int64_t line = line_ + 1;  // the first data row's line
  for (std::int64_t rows = 0; p != nullptr && p + 1 < end_ && rows < kLookaheadRows;) {
    const char* b = p + 1;
    const char* nl = static_cast<const char*>(
        std::memchr(b, '\n', static_cast<std::size_t>(end_ - b)));
    if (nl == nullptr && !eof_) break;  // a line cut by the end of the buffer
    const char* e = nl ? nl : end_;
    p = nl;
    ++line;
    if (e != b && e[-1] == '\r') --e;
    const char* q = skip_blanks(b, e);
    if (q == e || *q == '#' || *q == '%') continue;
    ++rows;
    if (count_fields(b, e, delimiter_) != fields_) continue;  // reported when it is parsed
    each(line, split_line(b, e, delimiter_, [] {}));
  }
}

void TextLog::fail(std::int64_t line, std::int64_t column, const std::string& message) const {
  throw ParseError(source_.name(), line, column, message);
}

void TextLog::refill() {
  const std::size_t keep = static_cast<std::size_t>(end_ - begin_);
  char* const base = buffer_.data();
  if (keep > 0 && begin_ != base) std::memmove(base, begin_, keep);
  begin_ = base;
  end_ = base + keep;
  const std::size_t got = source_.read(base + keep, block_bytes_);
  if (got == 0) eof_ = true;
  end_ += got;
}

bool TextLog::next_line(const char*& b, const char*& e) {
  for (;;) {
    const char* nl = static_cast<const char*>(
        std::memchr(begin_, '\n', static_cast<std::size_t>(end_ - begin_)));
    const char* stop = nl ? nl : end_;
    if (static_cast<std::size_t>(stop - begin_) > kMaxLineBytes) {
      fail(line_ + 1, 0,
           "line longer than " + std::to_string(kMaxLineBytes) +
               " bytes (the limit; is this a text log?)");
    }
    if (nl || (eof_ && begin_ != end_)) {
      b = begin_;
      e = stop;
      begin_ = nl ? nl + 1 : end_;
      ++line_;
      return true;
    }
    if (eof_) return false;
    refill();
  }
}

bool TextLog::next_content_line(const char*& b, const char*& e) {
  while (next_line(b, e)) {
    if (e != b && e[-1] == '\r') --e;
    const char* p = skip_blanks(b, e);
    if (p != e && *p != '#' && *p != '%') return true;
  }
  return false;
}

void TextLog::fail_ragged(const char* b, const char* e) const {
  const std::size_t found = count_fields(b, e, delimiter_);
  const std::size_t column = found < fields_ ? found + 1 : fields_ + 1;
  const bool semicolons = std::find(b, e, ';') != e;
  fail(line_, static_cast<std::int64_t>(column),
       "expected " + std::to_string(fields_) + " fields, found " + std::to_string(found) +
           (semicolons ? semicolon_hint("the line") : ""));
}

double TextLog::number_or_fail(const char* b, const char* e, std::size_t field) const {
  const std::string_view text(b, static_cast<std::size_t>(e - b));
  if (const auto v = to_number(text)) return *v;
  const std::string_view shown = trim_field(text);
  if (has_decimal_comma(shown)) {
    const int slot = selection_.slots[field];
    fail_decimal_comma(line_, field, shown,
                       slot >= 0 ? selection_.channel_names[static_cast<std::size_t>(slot)]
                                 : unnamed_column(field));
  }
  fail(line_, static_cast<std::int64_t>(field + 1),
       shown.empty() ? std::string("expected a number, found an empty field")
                     : "expected a number, found " + quote_field(shown) +
                           (shown.find(';') != std::string_view::npos ? semicolon_hint("the field")
                                                                       : ""));
}

void TextLog::time_or_fail(const char* b, const char* e, std::size_t field) {
  if (parse_time_stamp(std::string_view(b, static_cast<std::size_t>(e - b)), stamp_)) return;
  const std::string_view shown = trim_field(std::string_view(b, static_cast<std::size_t>(e - b)));
  fail(line_, static_cast<std::int64_t>(field + 1),
       "expected a number (time stamp), found " +
           (shown.empty() ? std::string("an empty field") : quote_field(shown)));
}

void TextLog::fail_nonfinite() const {
  for (std::size_t c = 0; c < fields_; ++c) {
    const int slot = selection_.slots[c];
    if (slot == kTimeColumn && !std::isfinite(stamp_.frac)) {
      fail(line_, static_cast<std::int64_t>(c + 1), "non-finite time stamp (NaN or Inf)");
    }
    if (slot >= 0 && !std::isfinite(row_[static_cast<std::size_t>(slot)])) {
      fail(line_, static_cast<std::int64_t>(c + 1),
           "non-finite value (NaN or Inf) in column \"" +
               selection_.channel_names[static_cast<std::size_t>(slot)] + "\"");
    }
  }
  SIGMATAU_ASSERT(false, "a non-finite row without a non-finite field");
  throw std::logic_error("unreachable");
}

template <TextLog::Mode M>
bool TextLog::parse_row(const char* b, const char* e) {
  const char d = delimiter_;
  const int* const slots = selection_.slots.data();
  double* const row = row_.data();
  bool finite = true;
  std::size_t f = 0;
  const char* p = M == Mode::whitespace ? skip_blanks(b, e) : b;
  for (;;) {
    if constexpr (M == Mode::whitespace) {
      if (p == e) break;
    }
    if (f == fields_) fail_ragged(b, e);
    const int slot = slots[f];
    const char* fe;
    if (slot >= 0) {
      double v;
      const auto r = std::from_chars(p, e, v);
      const bool ends = r.ptr == e || (M == Mode::whitespace ? is_blank(*r.ptr) : *r.ptr == d);
      if (r.ec == std::errc() && ends) {
        fe = r.ptr;
      } else {
        fe = M == Mode::whitespace ? find_blank(p, e) : find_char(p, e, d);
        // Not a number: an error, or under skip_row the row is dropped like one with a NaN.
        const auto parsed = to_number(std::string_view(p, static_cast<std::size_t>(fe - p)));
        v = parsed                                         ? *parsed
            : nonfinite_ == NonFinitePolicy::skip_row      ? std::numeric_limits<double>::quiet_NaN()
                                                           : number_or_fail(p, fe, f);
      }
      row[slot] = v;
      finite &= std::isfinite(v);
    } else {
      fe = M == Mode::whitespace ? find_blank(p, e) : find_char(p, e, d);
      if (slot == kTimeColumn) {
        time_or_fail(p, fe, f);
        finite &= std::isfinite(stamp_.frac);
      }
    }
    ++f;
    if constexpr (M == Mode::whitespace) {
      p = skip_blanks(fe, e);
    } else {
      if (fe == e) break;
      p = fe + 1;
    }
  }
  if (f != fields_) fail_ragged(b, e);
  if (!finite) {
    if (nonfinite_ == NonFinitePolicy::skip_row) return false;
    fail_nonfinite();
  }
  return true;
}

template <TextLog::Mode M>
std::int64_t TextLog::read_rows_as(SampleBlock& block, std::int64_t max_rows) {
  const std::size_t channels = row_.size();
  const bool timed = selection_.has_time;
  std::int64_t rows = 0;
  const char* b = nullptr;
  const char* e = nullptr;
  try {
    while (rows < max_rows && next_line(b, e)) {
      if (e != b && e[-1] == '\r') --e;
      const char* p = skip_blanks(b, e);
      if (p == e || *p == '#' || *p == '%') continue;
      if (!parse_row<M>(b, e)) {
        timing_.add_skipped();
        continue;
      }
      // Every check that can throw comes before the row enters the block (timing_.add refuses
      // a time column with too many segments): on a throw the block holds whole rows only.
      if (timed) timing_.add(stamp_, line_);
      for (std::size_t k = 0; k < channels; ++k) block.values[k].push_back(row_[k]);
      if (timed) block.t_s.push_back(timing_.seconds(stamp_));
      ++rows;
    }
  } catch (...) {
    if (!timed) timing_.add_untimed(rows);  // the rows kept before the error are counted
    throw;
  }
  if (!timed) timing_.add_untimed(rows);
  return rows;
}

std::int64_t TextLog::read_rows(SampleBlock& block, std::int64_t max_rows) {
  return mode_ == Mode::whitespace ? read_rows_as<Mode::whitespace>(block, max_rows)
                                   : read_rows_as<Mode::delimited>(block, max_rows);
}

}  // namespace sigmatau::detail
