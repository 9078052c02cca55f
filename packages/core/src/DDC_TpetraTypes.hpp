// The Tpetra types every package uses (default node, double scalars), so
// that contact, feti and analysis exchange vectors and maps of one kind.
#pragma once

#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

namespace ddc {

using Scalar = double;
using LO = Tpetra::Map<>::local_ordinal_type;
using GO = Tpetra::Map<>::global_ordinal_type;
using Node = Tpetra::Map<>::node_type;
using Map = Tpetra::Map<LO, GO, Node>;
using CrsMatrix = Tpetra::CrsMatrix<Scalar, LO, GO, Node>;
using CrsGraph = Tpetra::CrsGraph<LO, GO, Node>;
using MultiVector = Tpetra::MultiVector<Scalar, LO, GO, Node>;
using Vector = Tpetra::Vector<Scalar, LO, GO, Node>;

}  // namespace ddc
