// Text shared by every place that shows compliance verdicts (check's table, analyze's
// summary.md and report.html): ratios and the notes beside the verdict (see compliance.hpp).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "sigmatau/compliance.hpp"
#include "sigmatau/fit.hpp"

namespace sigmatau {

std::string format_ratio(double ratio) {
  if (!std::isfinite(ratio)) return "n/a";
  char text[48];
  if (std::abs(ratio) >= 100) {
    std::snprintf(text, sizeof text, "%.0f", ratio);
    return text;
  }
  // Three significant digits, four within 1 % of the limit; then more until a ratio that is not
  // exactly 1 no longer reads as 1 (a fail by 0.004 % must not print "1.000").
  int digits = std::abs(ratio - 1) < 0.01 ? 4 : 3;
  for (;; ++digits) {
    std::snprintf(text, sizeof text, "%#.*g", digits, ratio);
    if (ratio == 1 || digits >= 17 || std::strtod(text, nullptr) != 1) break;
  }
  std::string out = text;
  if (!out.empty() && out.back() == '.') out.pop_back();  // "%#g" keeps a bare point: "12."
  return out;
}

std::string verdict_qualifiers(bool within_uncertainty, double fit_p_value,
                               bool from_curve_readings) {
  std::string text = within_uncertainty ? "within uncertainty" : "";
  if (from_curve_readings) text += std::string(text.empty() ? "" : "; ") + "curve read-out";
  if (fit_p_value < kMisfitPValue) {
    char p[32];
    std::snprintf(p, sizeof p, "%.2g", fit_p_value);
    text += std::string(text.empty() ? "" : "; ") + "fit rejected, p = " + p;
  }
  return text;
}

std::string verdict_text(std::string_view verdict, bool within_uncertainty, double fit_p_value,
                         bool from_curve_readings) {
  const std::string qualifiers = verdict_qualifiers(within_uncertainty, fit_p_value, from_curve_readings);
  return std::string(verdict) + (qualifiers.empty() ? "" : " (" + qualifiers + ")");
}

bool any_typical_limit(const std::vector<ComplianceItem>& items) {
  for (const auto& item : items) {
    if (item.verdict != Verdict::not_specified && item.limit_is_typical) return true;
  }
  return false;
}

std::string gate_confidence_note(double confidence) {
  if (confidence >= 0.95 - 1e-9) return "";
  char level[32];
  std::snprintf(level, sizeof level, "%.3g", 100 * confidence);
  return std::string("At ") + level +
         " % a pass is a statement at about one sigma, and the bound of a term not detected "
         "(conditional on its non-detection) falls below the truth more often than that; for a "
         "gate, fit or analyze with --ci 0.95.";
}

}  // namespace sigmatau
