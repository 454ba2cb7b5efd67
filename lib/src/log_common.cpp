// Internal: number parsing, column selection and time-stamp statistics for the log readers
// (the gap policies' parsing and fill_gaps: log_gaps.cpp).
//
// Glossary: dt = interval between consecutive time stamps [s]; nominal = median dt of the first
// kMedianWindow intervals; a gap is dt > kGapFactor * nominal.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "log_internal.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/text_encoding.hpp"

namespace sigmatau::detail {
namespace {

/// Intervals kept for the exact median (kRateMedianIntervals, public: the CLI knows from it when
/// the rate is final): 100000 x 24 bytes = 2.4 MB at most; at 100 Hz that is the first 1000 s of
/// the log, plenty to fix the nominal rate of a clocked sensor.
constexpr auto kMedianWindow = static_cast<std::size_t>(kRateMedianIntervals);
/// An interval under this fraction of the nominal one is short. Together with the gaps it tells
/// jittered stamps (as many short intervals as long ones: the samples are all there) from lost
/// samples (no short intervals).
constexpr double kShortFactor = 0.5;
/// Gaps stored in the report (all are counted).
constexpr std::size_t kMaxStoredGaps = 1000;
/// Segments kept under GapPolicy::split: 8 MB of row indices at most (bounded memory); a log
/// broken more often than that has no contiguous stretch worth analysing.
constexpr std::size_t kMaxSegments = 1000000;
/// Column names listed in an "unknown column" message before "...".
constexpr std::size_t kMaxListedNames = 20;

bool is_blank(char c) { return c == ' ' || c == '\t'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), is_digit);
}

std::string format_seconds_ratio(double r) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g", r);
  return text;
}
double rate_hz_of(double nominal_s) { return nominal_s > 0 ? 1.0 / nominal_s : 0.0; }

}  // namespace

std::string unnamed_column(std::size_t index) {
  // Built by append: `"c" + to_string` trips GCC 12's false -Wrestrict, bug 105329.
  std::string name(1, 'c');
  name.append(std::to_string(index));
  return name;
}

std::string format_seconds(double s) {
  const double a = std::abs(s);
  const char* unit = "s";
  double v = s;
  if (a > 0 && a < 1e-6) {
    unit = "ns";
    v = s * 1e9;
  } else if (a > 0 && a < 1e-3) {
    unit = "us";
    v = s * 1e6;
  } else if (a > 0 && a < 1) {
    unit = "ms";
    v = s * 1e3;
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.4g %s", v, unit);
  return text;
}

std::string_view trim_field(std::string_view f) {
  while (!f.empty() && is_blank(f.front())) f.remove_prefix(1);
  while (!f.empty() && is_blank(f.back())) f.remove_suffix(1);
  if (f.size() >= 2 && f.front() == '"' && f.back() == '"') {
    f = f.substr(1, f.size() - 2);
    while (!f.empty() && is_blank(f.front())) f.remove_prefix(1);
    while (!f.empty() && is_blank(f.back())) f.remove_suffix(1);
  }
  if (f.size() >= 2 && f.front() == '+' && (is_digit(f[1]) || f[1] == '.')) f.remove_prefix(1);
  return f;
}

std::optional<double> to_number(std::string_view field) {
  const std::string_view f = trim_field(field);
  if (f.empty()) return std::nullopt;
  double v = 0;
  const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
  if (r.ptr != f.data() + f.size()) return std::nullopt;
  if (r.ec == std::errc()) return v;
  if (r.ec == std::errc::result_out_of_range) {
    // from_chars leaves v untouched; strtod gives +-HUGE_VAL (-> non-finite) or the underflow.
    const std::string copy(f);
    return std::strtod(copy.c_str(), nullptr);
  }
  return std::nullopt;
}

std::string shown_name(std::string_view raw) {
  return is_utf8(raw) ? std::string(raw) : utf8_from_windows1252(raw);
}

std::string quote_field(std::string_view field) {
  std::string out = "\"";
  out.append(escape_non_utf8(field.substr(0, kMaxQuotedField)));
  out += field.size() > kMaxQuotedField ? "...\"" : "\"";
  return out;
}

namespace {

/// True when the header fields hold control bytes (other than tab) or NUL: raw binary samples
/// read as text.
bool looks_binary(const std::vector<std::string>& names) {
  for (const std::string& n : names) {
    for (const char ch : n) {
      const auto b = static_cast<unsigned char>(ch);
      if ((b < 0x20 && b != '\t') || b == 0x7f) return true;
    }
  }
  return false;
}

/// A hint for a header the reader could not use: raw binary data, or fields separated by ';'
/// (a European CSV, which this reader does not split). "" when there is nothing to add.
std::string header_hint(const std::vector<std::string>& names) {
  if (looks_binary(names)) {
    return "; the file looks binary (control bytes in its first line): for raw samples give "
           "--binary i16|i32|f32|f64 and --channels C";
  }
  for (const std::string& n : names) {
    if (n.find(';') != std::string::npos) return semicolon_hint("the header");
  }
  return "";
}

}  // namespace

TimeColumnName time_column_name(std::string_view name) {
  std::string n(trim_field(name));
  for (char& ch : n) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  std::string base = n;
  std::string suffix;
  bool has_suffix = false;
  if (!n.empty() && (n.back() == ']' || n.back() == ')')) {
    // "time [ms]", "t(s)"
    const std::size_t open = n.find_last_of(n.back() == ']' ? '[' : '(');
    if (open == std::string::npos) return {};
    suffix = n.substr(open + 1, n.size() - open - 2);
    base = n.substr(0, open);
    has_suffix = true;
  } else if (const std::size_t sep = n.find_last_of("_ -"); sep != std::string::npos) {
    suffix = n.substr(sep + 1);  // "t_ms", "timestamp ns", "time-us"
    base = n.substr(0, sep);
    has_suffix = true;
  }
  while (!base.empty() && (base.back() == ' ' || base.back() == '_' || base.back() == '-')) {
    base.pop_back();
  }
  if (base != "t" && base != "time" && base != "timestamp") return {};
  if (!has_suffix) return {true, std::nullopt};
  static const std::pair<const char*, TimeUnit> units[] = {
      {"s", TimeUnit::s},      {"sec", TimeUnit::s},    {"ms", TimeUnit::ms},
      {"us", TimeUnit::us},    {"\xc2\xb5s", TimeUnit::us}, {"\xce\xbcs", TimeUnit::us},
      {"ns", TimeUnit::ns},    {"min", TimeUnit::min},  {"h", TimeUnit::h},
      {"d", TimeUnit::d},      {"day", TimeUnit::d},    {"days", TimeUnit::d},
      {"mjd", TimeUnit::d}};
  for (const auto& [text, unit] : units) {
    if (suffix == text) return {true, unit};
  }
  return {};  // "t_sensor", "time_offset": not a time column's name
}

std::string semicolon_hint(const std::string& where) {
  return "; " + where + " holds ';': fields are separated by commas, tabs or spaces, not ';' "
         "(convert it: decimal commas to points first, then ';' to ',')";
}

ColumnSelection select_columns(const std::vector<std::string>& names, bool has_header,
                               const std::vector<bool>& numeric, const LogOptions& options,
                               const std::string& file, std::int64_t names_line,
                               std::int64_t data_line, const std::string& what) {
  const std::size_t count = names.size();
  // Names are user data and every output needs them in UTF-8: one that is not (a Windows
  // program's "\xB0/s") is read as Windows-1252, here, once.
  std::vector<std::string> shown;
  for (const std::string& n : names) shown.push_back(shown_name(n));
  const auto label = [&](std::size_t c) {
    return has_header && !shown[c].empty() ? shown[c] : unnamed_column(c);
  };
  const std::string range = "0.." + std::to_string(count - 1);
  const auto resolve = [&](const std::string& spec, const std::string& role) -> int {
    if (spec.empty()) throw ParseError(file, names_line, 0, "empty " + role + " name");
    if (all_digits(spec)) {
      std::size_t index = 0;
      const auto r = std::from_chars(spec.data(), spec.data() + spec.size(), index);
      if (r.ec != std::errc() || index >= count) {
        throw ParseError(file, names_line, 0,
                         role + " index " + spec + " out of range: there are " +
                             std::to_string(count) + " " + what + "s (indices " + range + ")");
      }
      return static_cast<int>(index);
    }
    if (has_header) {
      std::vector<std::size_t> hits;
      for (std::size_t c = 0; c < count; ++c) {
        if (names[c] == spec || shown[c] == spec) hits.push_back(c);
      }
      if (hits.size() == 1) return static_cast<int>(hits[0]);
      if (hits.size() > 1) {
        throw ParseError(file, names_line, 0,
                         role + " name \"" + escape_non_utf8(spec) + "\" is ambiguous: it names columns " +
                             std::to_string(hits[0]) + " and " + std::to_string(hits[1]) +
                             "; use a 0-based index");
      }
    } else if (spec.size() > 1 && spec[0] == 'c' && all_digits(spec.substr(1))) {
      std::size_t index = 0;
      const auto r = std::from_chars(spec.data() + 1, spec.data() + spec.size(), index);
      if (r.ec == std::errc() && index < count) return static_cast<int>(index);
    }
    std::string message = "unknown " + role + " \"" + escape_non_utf8(spec) + "\"";
    if (has_header) {
      message += " (available: ";
      for (std::size_t c = 0; c < count && c < kMaxListedNames; ++c) {
        message += (c ? ", " : "") + label(c);
      }
      if (count > kMaxListedNames) message += ", ... (" + std::to_string(count) + " in all)";
      message += ")" + header_hint(names);
    } else {
      message += ": there is no header row; use 0-based indices " + range + " or names c0..c" +
                 std::to_string(count - 1);
    }
    throw ParseError(file, names_line, 0, message);
  };

  ColumnSelection sel;
  sel.slots.assign(count, kSkipColumn);
  int time_index = -1;
  if (!options.time_column.empty()) {
    time_index = resolve(options.time_column, "time " + what);
  } else if (options.find_time_column && has_header) {
    // A column named as time stamps, unless it is asked for as a channel.
    const auto asked = [&](std::size_t c) {
      return std::any_of(options.columns.begin(), options.columns.end(), [&](const std::string& s) {
        return s == names[c] || s == shown[c] || s == std::to_string(c);
      });
    };
    for (std::size_t c = 0; c < count; ++c) {
      if (time_column_name(shown[c]).is_time && !asked(c)) {
        sel.time_candidates.push_back(static_cast<int>(c));
      }
    }
    // Two or more (t and a temperature named T): the reader keeps the one whose values increase.
    if (sel.time_candidates.size() == 1) {
      time_index = sel.time_candidates.front();
      sel.time_column_found = shown[static_cast<std::size_t>(time_index)];
    }
  }
  if (time_index >= 0) {
    sel.slots[static_cast<std::size_t>(time_index)] = kTimeColumn;
    sel.has_time = true;
    const auto by_name = has_header ? time_column_name(shown[static_cast<std::size_t>(time_index)])
                                    : TimeColumnName{};
    if (options.time_unit) {
      sel.time_unit = *options.time_unit;
    } else if (by_name.unit) {
      sel.time_unit = *by_name.unit;
      sel.time_unit_from_name = true;
    }
  }
  const auto add_channel = [&](std::size_t c) {
    sel.slots[c] = static_cast<int>(sel.channel_columns.size());
    sel.channel_columns.push_back(static_cast<int>(c));
    sel.channel_names.push_back(label(c));
  };
  if (options.columns.empty()) {
    for (std::size_t c = 0; c < count; ++c) {
      if (sel.slots[c] == kSkipColumn && numeric[c]) add_channel(c);
    }
    if (sel.channel_columns.empty()) {
      throw ParseError(file, data_line, 0,
                       std::string("no numeric columns") +
                           (sel.has_time ? " besides the time column" : "") +
                           ": the first data row holds no number to analyse" +
                           header_hint(names));
    }
  } else {
    for (const std::string& spec : options.columns) {
      const auto c = static_cast<std::size_t>(resolve(spec, what));
      if (sel.slots[c] == kTimeColumn) {
        throw ParseError(
            file, names_line, 0,
            what + " \"" + spec + "\" is the time column; it cannot also be a channel");
      }
      if (sel.slots[c] >= 0) {
        throw ParseError(file, names_line, 0, what + " \"" + spec + "\" is selected twice");
      }
      add_channel(c);
    }
  }
  if (has_header) {
    std::size_t listed = 0, more = 0;
    for (std::size_t c = 0; c < count; ++c) {
      if (sel.slots[c] == kSkipColumn || shown[c] == names[c]) continue;
      if (listed == kMaxListedNames) {
        ++more;
        continue;
      }
      ++listed;
      sel.warnings.push_back("the name of column " + std::to_string(c) + ", \"" +
                             escape_non_utf8(names[c]) +
                             "\", is not UTF-8: it is read as Windows-1252 (Latin-1), \"" +
                             shown[c] + "\"");
    }
    if (more > 0) {
      sel.warnings.push_back(std::to_string(more) + " more column names are not UTF-8 and are "
                             "read as Windows-1252 (Latin-1)");
    }
  }
  return sel;
}

bool parse_time_stamp(std::string_view field, TimeStamp& stamp) {
  const std::string_view f = trim_field(field);
  const char* b = f.data();
  const char* e = b + f.size();
  std::int64_t whole = 0;
  const auto r = std::from_chars(b, e, whole);
  if (r.ec == std::errc() && r.ptr != b) {
    if (r.ptr == e) {
      stamp = {whole, 0.0};
      return true;
    }
    // "123.456": integer part exact, the fraction as a double (no exponent allowed here).
    if (*r.ptr == '.' && std::all_of(r.ptr + 1, e, is_digit)) {
      double frac = 0;
      if (r.ptr + 1 != e) std::from_chars(r.ptr, e, frac);
      stamp = {whole, *b == '-' ? -frac : frac};
      return true;
    }
  }
  const auto v = to_number(f);  // exponents, overflowing integers, nan/inf
  if (!v) return false;
  stamp = {0, *v};
  return true;
}

void TimingAccumulator::start(bool has_time, TimeUnit unit) {
  has_time_ = has_time;
  divisor_ = 1;
  multiplier_ = 1;
  switch (unit) {
    case TimeUnit::s:
      break;
    case TimeUnit::ms:
      divisor_ = 1e3;
      break;
    case TimeUnit::us:
      divisor_ = 1e6;
      break;
    case TimeUnit::ns:
      divisor_ = 1e9;
      break;
    case TimeUnit::min:
      multiplier_ = 60;
      break;
    case TimeUnit::h:
      multiplier_ = 3600;
      break;
    case TimeUnit::d:
      multiplier_ = 86400;
      break;
  }
}

double TimingAccumulator::seconds(const TimeStamp& s) const {
  return (static_cast<double>(s.whole) + s.frac) / divisor_ * multiplier_;
}

void TimingAccumulator::add(const TimeStamp& stamp, std::int64_t line) {
  const double t_s = seconds(stamp);
  if (samples_ > 0) {
    std::int64_t whole_step = 0;
    double step = 0;  // in the file's unit
    if (__builtin_sub_overflow(stamp.whole, prev_.whole, &whole_step)) {
      step = static_cast<double>(stamp.whole) - static_cast<double>(prev_.whole);
    } else {
      step = static_cast<double>(whole_step);
    }
    const double dt_s = (step + (stamp.frac - prev_.frac)) / divisor_ * multiplier_;
    ++intervals_;
    mean_all_ += (dt_s - mean_all_) / static_cast<double>(intervals_);
    if (!(dt_s > 0) && non_increasing_++ == 0) {
      first_ni_row_ = samples_;
      first_ni_line_ = line;
      first_ni_step_s_ = dt_s;
    }
    if (frozen_) {
      classify(classified_, nominal_s_, samples_, line, prev_s_, dt_s);
    } else {
      window_.push_back({dt_s, prev_s_, line});
      if (window_.size() >= kMedianWindow) freeze();
    }
  }
  prev_ = stamp;
  prev_s_ = t_s;
  ++samples_;
}

double TimingAccumulator::median(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

void TimingAccumulator::classify(Classified& c, double nominal_s, std::int64_t row,
                                 std::int64_t line, double start_s, double dt_s) const {
  const bool gap = nominal_s > 0 && dt_s > kGapFactor * nominal_s;
  if (policy_ == GapPolicy::split && (gap || !(dt_s > 0))) {
    if (c.breaks.size() >= kMaxSegments) {
      throw ParseError(file_, line, 0,
                       "more than " + std::to_string(kMaxSegments) +
                           " segments between gaps and non-increasing time stamps; the time "
                           "column is not usable (check --time-column and --time-unit)");
    }
    c.breaks.push_back(row);
  }
  if (!(dt_s > 0)) return;  // counted in non_increasing
  if (nominal_s > 0 && dt_s < kShortFactor * nominal_s) ++c.short_count;
  if (gap) {
    ++c.gap_count;
    if (c.gaps.size() < kMaxStoredGaps) c.gaps.push_back({row, line, start_s, dt_s});
    if (dt_s > c.largest_gap_s) {
      c.largest_gap_s = dt_s;
      c.largest_gap_line = line;
    }
    return;
  }
  ++c.regular;  // Welford's update
  const double delta = dt_s - c.mean;
  c.mean += delta / static_cast<double>(c.regular);
  c.m2 += delta * (dt_s - c.mean);
}

void TimingAccumulator::freeze() {
  std::vector<double> dts;
  dts.reserve(window_.size());
  for (const auto& w : window_) dts.push_back(w.dt_s);
  nominal_s_ = median(std::move(dts));
  for (std::size_t i = 0; i < window_.size(); ++i) {
    classify(classified_, nominal_s_, static_cast<std::int64_t>(i) + 1, window_[i].line,
             window_[i].start_s, window_[i].dt_s);
  }
  std::vector<Interval>().swap(window_);
  frozen_ = true;
}

void TimingAccumulator::finish() {
  if (has_time_ && !frozen_) freeze();
  if (!has_time_ || !(policy_ == GapPolicy::error || policy_ == GapPolicy::fill)) return;
  const auto ms = [](double s) { return format_seconds(s); };
  const bool gaps = policy_ == GapPolicy::error && classified_.gap_count > 0;
  const bool backwards = non_increasing_ > 0;
  if (!gaps && !backwards) return;
  const Gap* first = gaps ? &classified_.gaps.front() : nullptr;
  if (backwards && (!first || first_ni_row_ < first->row)) {
    throw ParseError(
        file_, first_ni_line_, 0,
        std::string(first_ni_step_s_ == 0 ? "duplicated time stamp" : "time stamp goes backwards") +
            " (step " + ms(first_ni_step_s_) + "), row " + std::to_string(first_ni_row_) + "; " +
            std::to_string(non_increasing_) + " non-increasing stamp" +
            (non_increasing_ == 1 ? "" : "s") + " in all" +
            (classified_.gap_count > 0
                 ? " and " + std::to_string(classified_.gap_count) + " gap(s)"
                 : std::string()) +
            "; use --gaps split to analyse the pieces apart (a logger restart), fix the time "
            "column (--time-column, --time-unit), or use --gaps report to analyse the rows as "
            "if contiguous");
  }
  static const std::string gap_advice =
      "; use --gaps split to analyse the contiguous segments apart, --gaps fill to "
      "interpolate the missing samples, or --gaps report to analyse the log as if contiguous";
  throw ParseError(
      file_, first->line, 0,
      "time stamp gap of " + ms(first->length_s) + " (" +
          format_seconds_ratio(first->length_s * rate_hz_of(nominal_s_)) +
          " nominal intervals of " + ms(nominal_s_) + ") before data row " +
          std::to_string(first->row) + "; " + std::to_string(classified_.gap_count) + " gap" +
          (classified_.gap_count == 1 ? "" : "s") + " in all, the largest " +
          ms(classified_.largest_gap_s) + " at line " +
          std::to_string(classified_.largest_gap_line) +
          // Rows out of order make a gap, a backwards step, and a gap: name the backwards one.
          (backwards ? std::string(", and ") + std::to_string(non_increasing_) +
                           (first_ni_step_s_ == 0 ? " duplicated or backwards" : " backwards") +
                           " stamp" + (non_increasing_ == 1 ? "" : "s") + ", the first at line " +
                           std::to_string(first_ni_line_) + " (rows out of order?)"
                     : std::string()) +
          (skipped_ > 0 ? "; " + std::to_string(skipped_) + " row" + (skipped_ == 1 ? " was" : "s were") +
                              " dropped by --nonfinite skip, and each leaves such a gap"
                        : std::string()) +
          (2 * classified_.short_count >= classified_.gap_count ? jitter_advice() : gap_advice));
}

std::string TimingAccumulator::jitter_advice() const {
  const double mean_rate_hz = mean_all_ > 0 ? 1.0 / mean_all_ : 0;
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.6g Hz", mean_rate_hz);
  return "; " + std::to_string(classified_.short_count) +
         " intervals are also under half the nominal one, so these look like jittered time "
         "stamps (receive times?) rather than lost samples: --gaps report analyses the rows as "
         "contiguous, and --rate fixes the interval (the mean interval says " + rate +
         "); --gaps fill would invent samples";
}

TimingReport TimingAccumulator::report() const {
  TimingReport r;
  r.samples = samples_;
  r.has_time = has_time_;
  r.rows_skipped_nonfinite = skipped_;
  r.header = header_;
  if (!has_time_) return r;
  r.non_increasing = non_increasing_;
  r.mean_interval_s = intervals_ > 0 ? mean_all_ : 0;
  double nominal_s = nominal_s_;
  Classified provisional;
  const Classified* c = &classified_;
  if (!frozen_) {
    std::vector<double> dts;
    dts.reserve(window_.size());
    for (const auto& w : window_) dts.push_back(w.dt_s);
    nominal_s = median(std::move(dts));
    for (std::size_t i = 0; i < window_.size(); ++i) {
      classify(provisional, nominal_s, static_cast<std::int64_t>(i) + 1, window_[i].line,
               window_[i].start_s, window_[i].dt_s);
    }
    c = &provisional;
  }
  r.rate_hz = nominal_s > 0 ? 1.0 / nominal_s : 0.0;
  r.jitter_s = c->regular > 1 ? std::sqrt(c->m2 / static_cast<double>(c->regular - 1)) : 0.0;
  r.gap_count = c->gap_count;
  r.gaps = c->gaps;
  r.largest_gap_s = c->largest_gap_s;
  r.largest_gap_line = c->largest_gap_line;
  r.first_non_increasing_row = first_ni_row_;
  r.first_non_increasing_line = first_ni_line_;
  r.first_non_increasing_step_s = first_ni_step_s_;
  if (policy_ == GapPolicy::split) {
    r.segment_starts.reserve(c->breaks.size() + 1);
    r.segment_starts.push_back(0);
    r.segment_starts.insert(r.segment_starts.end(), c->breaks.begin(), c->breaks.end());
  }
  return r;
}

}  // namespace sigmatau::detail

namespace sigmatau {

NonFinitePolicy parse_nonfinite_policy(std::string_view text) {
  if (text == "error") return NonFinitePolicy::error;
  if (text == "skip") return NonFinitePolicy::skip_row;
  throw Error("unknown non-finite policy \"" + std::string(text) + "\" (expected skip or error)");
}

}  // namespace sigmatau
