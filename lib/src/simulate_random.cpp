// Counter-based random streams: xoshiro256++ per sub-block, 128-layer ziggurat normals.
//
// Glossary: key = stream identity (seed, sensor, axis, term); S = kRandomSubBlock samples per
// sub-block; the generator of sub-block j is seeded by splitmix64 from hash(key, j).
#include "simulate_random.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "sigmatau/simulate.hpp"

namespace sigmatau::detail {
namespace {

std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  std::uint64_t x = a ^ (b * 0xD1B54A32D192ED03ULL);
  return splitmix64(x);
}

class Xoshiro256pp {
 public:
  explicit Xoshiro256pp(std::uint64_t seed) {
    for (auto& s : s_) s = splitmix64(seed);
  }
  std::uint64_t operator()() {
    const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform on (0, 1), never 0 or 1 (53 random bits, offset by half an ulp step).
  double uniform_open() { return (static_cast<double>((*this)() >> 11) + 0.5) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

/// Ziggurat tables for 128 layers. hz is a signed 57-bit integer (the random word shifted right
/// by the 7 layer bits), so the scale is 2^56.
struct Ziggurat {
  static constexpr int kLayers = 128;
  static constexpr double kR = 3.442619855899;             // start of the tail (Marsaglia-Tsang)
  static constexpr double kArea = 9.91256303526217e-3;     // area of each layer
  static constexpr double kScale = 72057594037927936.0;    // 2^56
  std::array<std::uint64_t, kLayers> k{};
  std::array<double, kLayers> w{};
  std::array<double, kLayers> f{};
  Ziggurat() {
    double dn = kR, tn = kR;
    const double q = kArea / std::exp(-0.5 * dn * dn);
    k[0] = static_cast<std::uint64_t>((dn / q) * kScale);
    k[1] = 0;
    w[0] = q / kScale;
    w[kLayers - 1] = dn / kScale;
    f[0] = 1.0;
    f[kLayers - 1] = std::exp(-0.5 * dn * dn);
    for (int i = kLayers - 2; i >= 1; --i) {
      dn = std::sqrt(-2.0 * std::log(kArea / dn + std::exp(-0.5 * dn * dn)));
      k[i + 1] = static_cast<std::uint64_t>((dn / tn) * kScale);
      tn = dn;
      f[i] = std::exp(-0.5 * dn * dn);
      w[i] = dn / kScale;
    }
  }
};

const Ziggurat& ziggurat() {
  static const Ziggurat table;
  return table;
}

inline double normal(Xoshiro256pp& rng, const Ziggurat& z) {
  for (;;) {
    const std::uint64_t u = rng();
    const int i = static_cast<int>(u & 127);
    const std::int64_t hz = static_cast<std::int64_t>(u) >> 7;
    const std::uint64_t ahz = static_cast<std::uint64_t>(hz < 0 ? -hz : hz);
    if (ahz < z.k[i]) return static_cast<double>(hz) * z.w[i];
    if (i == 0) {  // the tail beyond R (Marsaglia 1964)
      double x, y;
      do {
        x = -std::log(rng.uniform_open()) / Ziggurat::kR;
        y = -std::log(rng.uniform_open());
      } while (y + y < x * x);
      return hz > 0 ? Ziggurat::kR + x : -Ziggurat::kR - x;
    }
    const double x = static_cast<double>(hz) * z.w[i];
    if (z.f[i] + rng.uniform_open() * (z.f[i - 1] - z.f[i]) < std::exp(-0.5 * x * x)) return x;
  }
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

/// Calls gen(rng, out, n, stride) for each sub-block piece covering [first, first + count), the
/// values of sample first + i going to out[i * stride].
template <class Gen>
void fill(std::uint64_t key, std::int64_t first, std::int64_t count, double* out, Gen gen,
          std::int64_t stride = 1) {
  constexpr std::int64_t S = kRandomSubBlock;
  std::vector<double> scratch;
  std::int64_t k = first;
  const std::int64_t end = first + count;
  while (k < end) {
    const std::int64_t block = floor_div(k, S);
    const std::int64_t block_start = block * S;
    Xoshiro256pp rng(mix(key, static_cast<std::uint64_t>(block)));
    const std::int64_t offset = k - block_start;
    const std::int64_t n = std::min(S - offset, end - k);
    if (offset == 0 && n == S) {
      gen(rng, out + (k - first) * stride, S, stride);
    } else {
      scratch.resize(static_cast<std::size_t>(S));
      gen(rng, scratch.data(), S, std::int64_t{1});
      double* o = out + (k - first) * stride;
      for (std::int64_t i = 0; i < n; ++i) o[i * stride] = scratch[static_cast<std::size_t>(offset + i)];
    }
    k += n;
  }
}

}  // namespace

std::uint64_t stream_key(std::uint64_t seed, int sensor, int axis, int term) {
  std::uint64_t key = mix(0x5349474D41544155ULL, seed);  // "SIGMATAU"
  key = mix(key, static_cast<std::uint64_t>(sensor));
  key = mix(key, static_cast<std::uint64_t>(axis));
  return mix(key, static_cast<std::uint64_t>(term));
}

void fill_normal(std::uint64_t key, std::int64_t first, std::int64_t count, double* out) {
  const Ziggurat& z = ziggurat();
  fill(key, first, count, out, [&z](Xoshiro256pp& rng, double* o, std::int64_t n, std::int64_t) {
    for (std::int64_t i = 0; i < n; ++i) o[i] = normal(rng, z);
  });
}

void fill_normal_strided(std::uint64_t key, std::int64_t first, std::int64_t count, double* out,
                         std::int64_t stride) {
  const Ziggurat& z = ziggurat();
  fill(
      key, first, count, out,
      [&z](Xoshiro256pp& rng, double* o, std::int64_t n, std::int64_t step) {
        for (std::int64_t i = 0; i < n; ++i) o[i * step] = normal(rng, z);
      },
      stride);
}

void fill_uniform_centered(std::uint64_t key, std::int64_t first, std::int64_t count, double* out) {
  fill(key, first, count, out, [](Xoshiro256pp& rng, double* o, std::int64_t n, std::int64_t) {
    for (std::int64_t i = 0; i < n; ++i) o[i] = rng.uniform_open() - 0.5;
  });
}

}  // namespace sigmatau::detail
