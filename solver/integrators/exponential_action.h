// The action exp(t A) b of a matrix exponential on a vector, without forming exp(t A): a
// truncated Taylor series with scaling, t A = s (t A / s), each of the s pieces summed to degree
// at most m (Al-Mohy and Higham, "Computing the action of the matrix exponential, with an
// application to exponential integrators", SIAM J. Sci. Comput. 33(2), 2011, Algorithm 3.2).
// (m, s) minimise the products m s subject to ||t A - t mu I||_1 / s <= theta_m, theta_m the
// degree-m bound for a backward error of 2^-53 (their Table 3.1; m = 1..30 from Higham,
// "Functions of Matrices", 2008, Table A.3); each piece stops early once two terms in a row are
// below 2^-53 of the sum. The shift mu = trace(A) / n is taken out and put back as e^(t mu). This
// uses the 1-norm of A itself where the paper refines it by estimates of ||A^p||^(1/p), so for a
// highly non-normal A it may take more products than the paper's, never fewer digits.
//
// For the event method (event_driven.cpp) it replaces a dense exponential, O(n^3) once per mode
// and step level, by O(n^2 m s) per use: the choice between them is the caller's. A matrix at
// most kSparseDensity full (a ladder's or a rectifier bank's modes: O(n) entries) is multiplied
// as a sparse matrix, O(nnz m s) per use; relative_cost() tells the caller a product's cost
// against a dense one.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace lcs {

class ExponentialAction {
 public:
  ExponentialAction() = default;
  explicit ExponentialAction(const Eigen::MatrixXd& A);

  // The products with A that apply(t, ...) will take at most.
  long planned_products(double t) const;
  // One product's cost against a dense n x n one: nnz / n^2 when A is multiplied as sparse, else 1.
  double relative_cost() const { return relative_cost_; }
  // out = exp(t A) b; returns the products with A taken.
  long apply(double t, const Eigen::VectorXd& b, Eigen::VectorXd& out) const;

 private:
  struct Plan {
    int degree = 0;  // m
    long pieces = 1;  // s
  };
  Plan plan(double t) const;

  const Eigen::MatrixXd* A_ = nullptr;
  Eigen::SparseMatrix<double> sparse_;  // A, when sparse enough (relative_cost_ < 1)
  double relative_cost_ = 1;
  double mu_ = 0;
  double norm1_ = 0;  // ||A - mu I||_1
};

}  // namespace lcs
