#include "ramap/graph/fiedler.h"

#include <Spectra/SymEigsSolver.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace ramap {
namespace {

// y = L^+ P x with P the projection off the constant vector. For x orthogonal to 1, L z = x is
// solved by grounding node 0 (z_0 = 0; row 0 then holds because rows of L and entries of x sum to
// zero) and L^+ x is z minus its mean. The largest eigenvalue of this operator is 1 / lambda_2.
class LaplacianPseudoInverseOp {
 public:
  using Scalar = double;
  explicit LaplacianPseudoInverseOp(const Eigen::SparseMatrix<double>& laplacian)
      : n_(laplacian.rows()) {
    const Eigen::SparseMatrix<double> grounded = laplacian.bottomRightCorner(n_ - 1, n_ - 1);
    solver_.compute(grounded);
    if (solver_.info() != Eigen::Success) {
      throw std::runtime_error("FiedlerValue: grounded Laplacian is not positive definite");
    }
  }
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, n_);
    Eigen::Map<Eigen::VectorXd> y(y_out, n_);
    const Eigen::VectorXd px = x.array() - x.mean();
    y(0) = 0.0;
    y.tail(n_ - 1) = solver_.solve(px.tail(n_ - 1));
    y.array() -= y.mean();
  }

 private:
  Eigen::Index n_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace

double FiedlerValue(const RotationGraph& graph, bool weighted, const std::vector<bool>& keep) {
  const int n = static_cast<int>(graph.node_ids.size());
  if (n < 2) return 0.0;
  const std::vector<int> components = ConnectedComponents(graph, keep);
  if (*std::max_element(components.begin(), components.end()) > 0) return 0.0;

  const auto index = NodeIndex(graph);
  std::vector<Eigen::Triplet<double>> triplets;
  std::set<std::pair<int, int>> seen;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!keep.empty() && !keep[e]) continue;
    int a = index.at(graph.edges[e].i);
    int b = index.at(graph.edges[e].j);
    if (a > b) std::swap(a, b);
    double w = 1.0;
    if (weighted) {
      w = graph.edges[e].weight;
    } else if (!seen.insert({a, b}).second) {
      continue;
    }
    triplets.emplace_back(a, a, w);
    triplets.emplace_back(b, b, w);
    triplets.emplace_back(a, b, -w);
    triplets.emplace_back(b, a, -w);
  }
  Eigen::SparseMatrix<double> laplacian(n, n);
  laplacian.setFromTriplets(triplets.begin(), triplets.end());

  if (n <= 3) {  // Lanczos needs a subspace larger than one vector; tiny graphs go dense.
    const Eigen::MatrixXd dense_laplacian(laplacian);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(dense_laplacian);
    return dense.eigenvalues()(1);
  }
  LaplacianPseudoInverseOp op(laplacian);
  const int ncv = std::min(n - 1, 20);
  Spectra::SymEigsSolver<LaplacianPseudoInverseOp> eigs(op, 1, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 1000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful) {
    throw std::runtime_error("FiedlerValue: Lanczos iteration did not converge");
  }
  return 1.0 / eigs.eigenvalues()(0);
}

double StrongDualityResidualBound(double lambda2, int max_degree) {
  if (lambda2 <= 0.0 || max_degree <= 0) return 0.0;
  const double s = std::sqrt(0.25 + lambda2 / (2.0 * max_degree)) - 0.5;
  return 2.0 * std::asin(std::min(1.0, s));
}

}  // namespace ramap
