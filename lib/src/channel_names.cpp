// The sensor and axis a column's name says it holds (channel_names.hpp).
#include "sigmatau/channel_names.hpp"

#include <cctype>
#include <string>

namespace sigmatau {

std::optional<ChannelRole> classify_channel(std::string_view name) {
  std::string n;
  for (const char c : name) n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (n.empty()) return std::nullopt;
  const char last = n.back();
  if (last != 'x' && last != 'y' && last != 'z') return std::nullopt;
  ChannelRole role;
  role.axis = last - 'x';
  const std::string stem = n.substr(0, n.size() - 1);
  auto starts = [&](const char* p) { return stem.rfind(p, 0) == 0; };
  auto has = [&](const char* p) { return stem.find(p) != std::string::npos; };
  if (stem == "g" || stem == "w" || starts("gyr") || starts("omega") || has("angular") ||
      stem == "g_" || stem == "w_" || stem == "wb_" || starts("rate_")) {
    role.sensor = Sensor::gyro;
    return role;
  }
  if (stem == "a" || stem == "a_" || starts("acc") || has("linear_acc") || stem == "f" || stem == "f_") {
    role.sensor = Sensor::accel;
    return role;
  }
  return std::nullopt;
}

}  // namespace sigmatau
