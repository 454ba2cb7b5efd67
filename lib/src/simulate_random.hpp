#pragma once
// Counter-based random streams for the simulator (internal). A stream is identified by a 64-bit
// key (seed, sensor, axis, term); sample index k belongs to sub-block k / kRandomSubBlock, whose
// generator is seeded from (key, sub-block index) alone. Normals come from a 128-layer ziggurat
// (Marsaglia & Tsang, "The Ziggurat Method for Generating Random Variables", J. Stat. Softw. 5(8),
// 2000) driven by xoshiro256++ (Blackman & Vigna 2018).
#include <cstdint>

namespace sigmatau::detail {

/// Mixes the parts of a stream identity into one key.
std::uint64_t stream_key(std::uint64_t seed, int sensor, int axis, int term);

/// Unit normals for sample indices [first, first + count) of stream `key` into out[0..count).
void fill_normal(std::uint64_t key, std::int64_t first, std::int64_t count, double* out);
/// The same normals written every `stride` doubles: out[i * stride], i < count (e.g. into the real
/// or imaginary parts of an interleaved complex array).
void fill_normal_strided(std::uint64_t key, std::int64_t first, std::int64_t count, double* out,
                         std::int64_t stride);

/// Uniforms on (-1/2, 1/2) for sample indices [first, first + count) of stream `key`.
void fill_uniform_centered(std::uint64_t key, std::int64_t first, std::int64_t count, double* out);

}  // namespace sigmatau::detail
