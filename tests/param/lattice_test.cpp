// Rounding lattices (thesis 4.2.2): round_to_lattice returns a point of the lattice and no lattice point is closer
// (checked against a brute-force search), distance_to_gaussian_integers against the same search over Z[i].
#include "param/lattice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/errors.h"

namespace quadcover {
namespace {

using C = std::complex<double>;

bool in_lattice(C p, Lattice lattice) {
  const double a = p.real(), b = p.imag();
  if (a != std::round(a) || b != std::round(b)) return false;
  const long ia = std::lround(a), ib = std::lround(b);
  switch (lattice) {
    case Lattice::Unit:
      return true;
    case Lattice::Coarse:
      return ia % 2 == 0 && ib % 2 == 0;
    case Lattice::Rotated:
      return (ia - ib) % 2 == 0;  // (1+i)(x+iy) = (x−y) + i(x+y): a ≡ b mod 2
  }
  return false;
}

// The smallest distance from z to a lattice point with integer coordinates within 4 of z.
double brute_force_distance(C z, Lattice lattice) {
  double best = INFINITY;
  for (long a = std::lround(z.real()) - 4; a <= std::lround(z.real()) + 4; ++a)
    for (long b = std::lround(z.imag()) - 4; b <= std::lround(z.imag()) + 4; ++b)
      if (in_lattice(C(a, b), lattice)) best = std::min(best, std::abs(z - C(a, b)));
  return best;
}

TEST(Lattice, RoundingGivesTheNearestLatticePoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-50, 50);
  for (Lattice lattice : {Lattice::Unit, Lattice::Coarse, Lattice::Rotated})
    for (int i = 0; i < 2000; ++i) {
      const C z(u(rng), u(rng));
      const C p = round_to_lattice(z, lattice);
      ASSERT_TRUE(in_lattice(p, lattice)) << to_string(lattice) << " " << z << " -> " << p;
      EXPECT_NEAR(std::abs(z - p), brute_force_distance(z, lattice), 1e-12) << to_string(lattice) << " " << z;
    }
}

TEST(Lattice, LatticePointsAreFixedAndRoundingIsTranslationInvariant) {
  // Each lattice is a group: rounding commutes with a shift by one of its points.
  const C shift[] = {C(3, -7), C(2, 4), C(3, 5)};  // a point of Unit, Coarse, Rotated
  int k = 0;
  for (Lattice lattice : {Lattice::Unit, Lattice::Coarse, Lattice::Rotated}) {
    ASSERT_TRUE(in_lattice(shift[k], lattice));
    EXPECT_EQ(round_to_lattice(shift[k], lattice), shift[k]);
    for (const C z : {C(0.3, 0.2), C(-1.4, 0.9), C(0.41, -0.27)})  // off the Voronoi boundaries (no ties)
      EXPECT_NEAR(std::abs(round_to_lattice(z + shift[k], lattice) - (round_to_lattice(z, lattice) + shift[k])), 0,
                  1e-12);
    ++k;
  }
  // The rotated lattice has index 2 in Z[i], the coarse one index 4: covering radii 1/√2, 1, √2.
  EXPECT_NEAR(std::abs(C(0.5, 0.5) - round_to_lattice(C(0.5, 0.5), Lattice::Unit)), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(std::abs(C(1, 0) - round_to_lattice(C(1, 0), Lattice::Rotated)), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(C(1, 1) - round_to_lattice(C(1, 1), Lattice::Coarse)), std::sqrt(2.0), 1e-15);
}

TEST(Lattice, DistanceToGaussianIntegersMatchesBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int i = 0; i < 1000; ++i) {
    const C z(u(rng), u(rng));
    EXPECT_NEAR(distance_to_gaussian_integers(z), brute_force_distance(z, Lattice::Unit), 1e-12) << z;
  }
  EXPECT_EQ(distance_to_gaussian_integers(C(-3, 8)), 0);
}

TEST(Lattice, NamesRoundTripAndUnknownNamesThrow) {
  for (Lattice lattice : {Lattice::Unit, Lattice::Coarse, Lattice::Rotated})
    EXPECT_EQ(parse_lattice(to_string(lattice)), lattice);
  EXPECT_THROW(parse_lattice("hexagonal"), InputError);
  EXPECT_THROW(parse_lattice(""), InputError);
}

}  // namespace
}  // namespace quadcover
