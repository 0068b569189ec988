#pragma once
// Random: a seeded xoshiro256** generator (state from splitmix64), identical on every
// platform and compiler, unlike the distributions of <random>. For Monte Carlo blocks and
// synthetic surfaces, which must be reproducible from a seed.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

namespace btflut {

class Random {
public:
    explicit Random(std::uint64_t seed) {
        for (auto& s : m_state) s = splitmix(seed);
    }
    std::uint64_t next() {
        const std::uint64_t result = rotl(m_state[1] * 5, 7) * 9;
        const std::uint64_t t = m_state[1] << 17;
        m_state[2] ^= m_state[0];
        m_state[3] ^= m_state[1];
        m_state[1] ^= m_state[2];
        m_state[0] ^= m_state[3];
        m_state[2] ^= t;
        m_state[3] = rotl(m_state[3], 45);
        return result;
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    // Two independent standard normals (Box-Muller).
    std::pair<double, double> normals() {
        const double u = 1 - uniform(), v = uniform();
        const double radius = std::sqrt(-2 * std::log(u));
        return {radius * std::cos(2 * std::numbers::pi * v), radius * std::sin(2 * std::numbers::pi * v)};
    }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    static std::uint64_t splitmix(std::uint64_t& x) {
        std::uint64_t z = (x += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    std::uint64_t m_state[4];
};

}  // namespace btflut
