#ifndef igabde_discretization_body_linear_solver_h
#define igabde_discretization_body_linear_solver_h

// Inside the library only: the factorisation a Body keeps (its pimpl),
// shared by the files that define Body's members.

#include <igabde/linear_algebra/sparse_cholesky.h>

#include <igabde/discretization/body.h>

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <memory>

namespace igabde
{
  namespace discretization
  {
    /**
     * The factorisation of the constrained stiffness, one of three paths
     * chosen by DiscretizationSettings::linear_solver.
     */
    template <int dim>
    struct Body<dim>::LinearSolver
    {
      /// Direct path (Linear solver = direct): MUMPS LDL^T, with the Schur
      /// complement onto the contact face when asked.
      std::unique_ptr<linear_algebra::SparseCholesky> cholesky;
      /// K with the constrained rows and columns replaced by a scaled
      /// identity (umfpack and cg-amg).
      SparseMatrix<double> constrained_matrix;
      /// LU path (Linear solver = umfpack).
      std::unique_ptr<SparseDirectUMFPACK> direct_solver;
      /// Iterative path (Linear solver = cg-amg): the constrained matrix as
      /// a Trilinos matrix and its ML algebraic multigrid preconditioner.
      std::unique_ptr<TrilinosWrappers::SparseMatrix>    amg_matrix;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    };
  } // namespace discretization
} // namespace igabde

#endif
