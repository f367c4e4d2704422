// Algebraic connectivity (Fiedler value): the second-smallest eigenvalue lambda_2 of the graph
// Laplacian L = D - A. It enters the strong-duality bound on rotation-averaging residuals of
// Eriksson, Olsson, Kahl and Chin ("Rotation averaging and strong duality", CVPR 2018), which is
// stated for the UNWEIGHTED Laplacian of the view graph (their chordal cost has unit weights).
#pragma once

#include <vector>

#include "ramap/graph/rotation_graph_algorithms.h"

namespace ramap {

// lambda_2 of the Laplacian of the graph made of the edges with keep[e] (all when `keep` is
// empty) and every node of `graph`. Parallel edges count once in the unweighted Laplacian; with
// `weighted` the weights of parallel edges add up. 0 for a disconnected graph or fewer than two
// nodes. Computed with Spectra (Lanczos) on the pseudo-inverse L^+ restricted to the complement of
// the constant vector, applied through a sparse Cholesky factor of the grounded Laplacian, so
// that small lambda_2 (long paths) converge as fast as large ones.
double FiedlerValue(const RotationGraph& graph, bool weighted = false,
                    const std::vector<bool>& keep = {});

// The largest angular residual (radians) under which Eriksson et al. (CVPR 2018, the corollary of
// their main theorem) guarantee strong duality, i.e. a stationary point of the chordal cost with
// all residuals below it is the global optimum:
//   alpha_max = 2 asin( sqrt(1/4 + lambda_2 / (2 d_max)) - 1/2 ),
// lambda_2 the Fiedler value of the unweighted Laplacian, d_max the largest node degree.
// 0 when lambda_2 <= 0 or d_max == 0. The paper (arXiv 1705.01362, extended in TPAMI 2019
// "Rotation averaging with the chordal distance: global minimizers and strong duality") states the
// condition for the unweighted chordal cost, hence the unweighted Laplacian and unweighted
// degrees. The formula is not checked against the corollary's own text: it is the one of
// docs/architecture.md (stage 3), checked for consistency: K_3 gives 60 deg, K_n tends to 42.9
// deg, sparse view graphs (lambda_2 ~ 1e-3) give hundredths of a degree.
// Example: a complete graph K_n, lambda_2 = n, d_max = n - 1, tends to 2 asin(sqrt(3/4) - 1/2)
// = 42.9 deg.
double StrongDualityResidualBound(double lambda2, int max_degree);

}  // namespace ramap
