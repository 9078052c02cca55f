// Read access to the local rows of a fill-complete Tpetra::CrsMatrix as plain
// CSR arrays, taken once per matrix instead of once per row.
//
// CrsMatrix::getLocalRowView() builds two reference-counted Kokkos views per
// call; in the loops that copy a subdomain matrix into its blocks in every
// Newton iteration (FETI-DP's K_rr, K_II, T^T K T, CHOLMOD's refresh) the
// counting and its mutex were 10-18 % of a nonlinear FETI-DP run
// (doc/performance.md, "The other contact problems").
#pragma once

#include <cstddef>

#include "DDC_TpetraTypes.hpp"

namespace ddc {

/// The local CSR arrays of `K` (fill-complete, locally indexed): row lr has
/// the entries ptr[lr] .. ptr[lr + 1] - 1, local column col[e] (in K's column
/// map) and value val[e]. Valid while K's values and pattern are not
/// reallocated (resumeFill / replaceLocalValues keep them).
class LocalCsr {
 public:
  explicit LocalCsr(const CrsMatrix& K)
      : A_(K.getLocalMatrixHost()),
        ptr(A_.graph.row_map.data()),
        col(A_.graph.entries.data()),
        val(A_.values.data()),
        rows(static_cast<LO>(A_.numRows())) {}

 private:
  CrsMatrix::local_matrix_host_type A_;  // holds the views

 public:
  const std::size_t* ptr;
  const LO* col;
  const double* val;
  const LO rows;
};

}  // namespace ddc
