// Perlin's improved noise against values printed by his reference Java implementation
// (ImprovedNoise.java, 2002), run with OpenJDK: bit-for-bit equality.
#include <gtest/gtest.h>

#include "jellysim/geometry/perlin.hpp"

namespace jellysim::geometry {
namespace {

struct Reference {
  double x, y, z, value;
};

// Output of ImprovedNoise.noise(x, y, z) (Java doubles, printed with Double.toString).
constexpr Reference kReference[] = {
    {3.14, 42.0, 7.0, 0.13691995878400012},
    {0.5, 0.5, 0.5, -0.25},
    {1.25, -2.75, 3.5, 0.12009716033935547},
    {-7.3, 0.1, 12.9, -0.44753895935999943},
    {100.01, 200.02, 300.03, 0.029808855316279272},
    {0.3, 8.7, -0.01, 0.33018252562631867},
    {-0.5, -1.25, -3.125, -0.03572364151477814},
    {255.5, 256.5, 257.5, 0.0},
    {17.17, -34.34, 0.0, 0.11388687008720058},
    {2.0, 4.0, 6.5, -0.25},
    {0.9999, 1.0E-4, 0.5, -0.5000999999849993},
    {-123.456, 78.9, 0.321, 0.10791134883609751},
    {0.1, 0.2, 0.3, 0.35122924878110723},
    {1.7, 0.0, 0.04, 0.3589510910875239},
    {0.33, 2.66, 0.0, -0.2958672049488415},
};

TEST(PerlinNoise, MatchesReferenceImplementationBitForBit) {
  for (const Reference& r : kReference) {
    EXPECT_EQ(perlin_noise(r.x, r.y, r.z), r.value) << "at (" << r.x << ", " << r.y << ", " << r.z << ")";
  }
}

TEST(PerlinNoise, SeedZeroIsTheReferenceAndOtherSeedsDiffer) {
  const ImprovedNoise reference(0), other(7), same(7);
  int differing = 0;
  for (const Reference& r : kReference) {
    EXPECT_EQ(reference(r.x, r.y, r.z), r.value);
    EXPECT_EQ(other(r.x, r.y, r.z), same(r.x, r.y, r.z));  // deterministic
    if (other(r.x, r.y, r.z) != r.value) ++differing;
  }
  EXPECT_GE(differing, 10);
}

TEST(PerlinNoise, ZeroOnLatticeBoundedAndContinuous) {
  const ImprovedNoise noise(3);
  EXPECT_EQ(noise(1.0, 2.0, 3.0), 0.0);
  double max_abs = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double x = 0.0137 * k, y = 0.7 + 0.0091 * k, z = 0.3 - 0.0053 * k;
    const double v = noise(x, y, z);
    max_abs = std::max(max_abs, std::abs(v));
    // Lipschitz-like continuity: a step of 1e-6 changes the value by far less than 1e-4.
    EXPECT_LT(std::abs(noise(x + 1e-6, y, z) - v), 1e-4);
  }
  EXPECT_LE(max_abs, 1.0);
  EXPECT_GT(max_abs, 0.3);
}

}  // namespace
}  // namespace jellysim::geometry
