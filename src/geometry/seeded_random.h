// A random number generator whose output is the same on every platform: xoshiro256**.
//
// The standard library's distributions are implementation-defined (libstdc++ and libc++
// give different numbers for the same engine), so the random lattice draws its numbers
// here: 64-bit words from xoshiro256** (Blackman and Vigna), its state seeded by
// splitmix64, doubles from the top 53 bits. Only integer arithmetic and one exact scaling.
#pragma once

#include <cstddef>
#include <cstdint>

namespace latfrac {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) {
    for (std::uint64_t& word : state_) {
      seed += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      word = z ^ (z >> 31);
    }
  }

  std::uint64_t next() {
    const std::uint64_t result = rotate_left(state_[1] * 5, 7) * 9;
    const std::uint64_t shifted = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= shifted;
    state_[3] = rotate_left(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // An index in [0, count); the modulo bias is below 2^-40 for the counts used here.
  std::size_t index(std::size_t count) { return static_cast<std::size_t>(next() % count); }

 private:
  static std::uint64_t rotate_left(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

}  // namespace latfrac
