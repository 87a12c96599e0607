// Rounding lattices (thesis 4.2.2).
#include "param/lattice.h"

#include <cmath>

#include "common/errors.h"

namespace quadcover {

Lattice parse_lattice(const std::string& name) {
  if (name == "unit") return Lattice::Unit;
  if (name == "coarse") return Lattice::Coarse;
  if (name == "rotated") return Lattice::Rotated;
  throw InputError("", 0, "unknown lattice '" + name + "' (expected unit, coarse or rotated)");
}

const char* to_string(Lattice lattice) {
  switch (lattice) {
    case Lattice::Unit: return "unit";
    case Lattice::Coarse: return "coarse";
    default: return "rotated";
  }
}

std::complex<double> round_to_lattice(std::complex<double> z, Lattice lattice) {
  auto round_gauss = [](std::complex<double> w) { return std::complex<double>(std::round(w.real()), std::round(w.imag())); };
  switch (lattice) {
    case Lattice::Unit: return round_gauss(z);
    case Lattice::Coarse: return 2.0 * round_gauss(0.5 * z);
    default: {
      const std::complex<double> g(1, 1);  // (1+i)Z[i] is Z[i] turned by 45° and scaled by √2
      return g * round_gauss(z / g);
    }
  }
}

double distance_to_gaussian_integers(std::complex<double> z) {
  return std::abs(z - std::complex<double>(std::round(z.real()), std::round(z.imag())));
}

}  // namespace quadcover
