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

Eigen::MatrixXd lattice_basis(Lattice lattice, int m) {
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(m, m);
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  switch (lattice) {
    case Lattice::Unit:
      T = Eigen::MatrixXd::Identity(2 * m, 2 * m);
      break;
    case Lattice::Coarse:
      T = 2 * Eigen::MatrixXd::Identity(2 * m, 2 * m);
      break;
    case Lattice::Rotated:
      T.topLeftCorner(m, m) = I;
      T.topRightCorner(m, m) = -I;
      T.bottomLeftCorner(m, m) = I;
      T.bottomRightCorner(m, m) = I;
      break;
  }
  return T;
}

}  // namespace quadcover
