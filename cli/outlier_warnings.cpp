#include "outlier_warnings.hpp"

#include "channel_units.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::cli {

ChannelOutliers::ChannelOutliers(const std::vector<std::string>& names,
                                 const std::vector<ChannelUnit>& units, DataKind kind) {
  if (names.size() != units.size()) {
    throw Error("outlier check: " + std::to_string(names.size()) + " channels but " +
                std::to_string(units.size()) + " units");
  }
  OutlierOptions options;  // analyze's: the defaults, on differences for phase data
  options.differences = kind == DataKind::phase;
  checkers_.reserve(names.size());
  for (std::size_t c = 0; c < names.size(); ++c) {
    const ChannelUnit& u = units[c];
    const bool known = !u.unit.empty() && u.to_si > 0 && u.result_to_si > 0;
    // A held value x result_to_si is SI; / to_si puts it in the declared unit.
    checkers_.emplace_back(names[c], options, known ? u.unit : std::string(),
                           known ? u.to_si / u.result_to_si : 1.0);
  }
}

void ChannelOutliers::add(std::size_t channel, std::span<const double> values) {
  checkers_.at(channel).add(values);
}

std::vector<std::string> ChannelOutliers::finish() {
  std::vector<std::string> messages;
  for (OutlierChecker& checker : checkers_) {
    if (const auto w = checker.finish()) messages.push_back(w->message);
  }
  return messages;
}

BlockOutliers::BlockOutliers(const LogArguments& args, DataKind kind, bool background)
    : args_(args), kind_(kind), background_(background) {}

BlockOutliers::~BlockOutliers() {
  if (job_.valid()) job_.wait();  // an exception elsewhere: its result is not wanted
}

void BlockOutliers::wait() {
  if (job_.valid()) job_.get();
}

void BlockOutliers::add(const std::vector<std::string>& names,
                        const std::vector<std::vector<double>>& values, bool in_background) {
  wait();
  if (!outliers_) {
    outliers_.emplace(names, channel_units_of(args_, names, sensors_by_name(names), false), kind_);
  }
  if (!in_background || !background_) {
    for (std::size_t c = 0; c < values.size(); ++c) outliers_->add(c, values[c]);
    return;
  }
  copy_.resize(values.size());
  for (std::size_t c = 0; c < values.size(); ++c) copy_[c].assign(values[c].begin(), values[c].end());
  job_ = std::async(std::launch::async, [this] {
    for (std::size_t c = 0; c < copy_.size(); ++c) outliers_->add(c, copy_[c]);
  });
}

std::vector<std::string> BlockOutliers::finish() {
  wait();
  return outliers_ ? outliers_->finish() : std::vector<std::string>{};
}

std::vector<std::string> outlier_warnings(const std::vector<std::vector<double>>& channels,
                                          const std::vector<std::string>& names,
                                          const std::vector<ChannelUnit>& units, DataKind kind) {
  ChannelOutliers outliers(names, units, kind);
  for (std::size_t c = 0; c < channels.size(); ++c) outliers.add(c, channels[c]);
  return outliers.finish();
}

}  // namespace sigmatau::cli
