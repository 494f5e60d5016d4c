#ifndef igabde_discretization_settings_h
#define igabde_discretization_settings_h

#include <igabde/base/choice_names.h>

#include <cmath>
#include <string>

namespace igabde
{
  namespace discretization
  {
    /** @brief Discretization/Type: how a body's displacement is discretised. */
    enum class Type
    {
      /// Isogeometric: the NURBS basis of the exact geometry.
      nurbs,
      /// deal.II's FE_Q on a mesh of the same NURBS map.
      lagrange
    };

    /** @brief Discretization/Linear solver. */
    enum class LinearSolver
    {
      /// MUMPS (LDL^T, with a Schur interface where the path asks).
      direct,
      /// UMFPACK (LU).
      umfpack,
      /// Conjugate gradients with Trilinos ML algebraic multigrid.
      cg_amg
    };

    /**
     * @brief Contact/Pair placement: where contact pair points sit on a
     * NURBS face. A Lagrange body uses its face nodes whatever this says.
     */
    enum class PairPlacement
    {
      /// Images of the Greville abscissae.
      greville,
      /// The knot grid.
      knots,
      /// The face's Gauss points.
      gauss
    };

    /** @brief The names of each enum's values as the scene writes them. */
    inline constexpr base::ChoiceNames<Type, 2> type_names = {
      {{Type::nurbs, "nurbs"}, {Type::lagrange, "lagrange"}}};
    /** @copydoc type_names */
    inline constexpr base::ChoiceNames<LinearSolver, 3> linear_solver_names = {
      {{LinearSolver::direct, "direct"},
       {LinearSolver::umfpack, "umfpack"},
       {LinearSolver::cg_amg, "cg-amg"}}};
    /** @copydoc type_names */
    inline constexpr base::ChoiceNames<PairPlacement, 3> pair_placement_names =
      {{{PairPlacement::greville, "greville"},
        {PairPlacement::knots, "knots"},
        {PairPlacement::gauss, "gauss"}}};

    /** @brief The name of each value as the scene writes it. */
    inline std::string
    to_string(const Type type)
    {
      return base::name_of(type_names, type);
    }
    /** @copydoc to_string(const Type) */
    inline std::string
    to_string(const LinearSolver solver)
    {
      return base::name_of(linear_solver_names, solver);
    }
    /** @copydoc to_string(const Type) */
    inline std::string
    to_string(const PairPlacement placement)
    {
      return base::name_of(pair_placement_names, placement);
    }

    /**
     * @brief How the scene discretises bodies.
     */
    struct DiscretizationSettings
    {
      Type type = Type::nurbs;
      /// Polynomial degree (NURBS: degree after elevation; Lagrange: FE_Q).
      unsigned int degree = 2;
      /// Extra uniform h-refinements of the scene's base mesh.
      unsigned int refinements   = 0;
      LinearSolver linear_solver = LinearSolver::direct;
      /// Relative tolerance of the iterative solver.
      double linear_tolerance = 1e-12;
      /// Subdivisions per cell and direction in the VTU output; 0: auto
      /// (output_subdivisions_for()).
      unsigned int  output_subdivisions = 0;
      PairPlacement pair_placement      = PairPlacement::greville;
    };

    /**
     * @brief The VTU output's subdivisions per cell and direction for a
     * body of @p n_cells cells: @p setting where it is set (not 0), else
     * the largest number up to 4 with at most 8192 sub-cells per body.
     */
    template <int dim>
    unsigned int
    output_subdivisions_for(const unsigned int setting, const double n_cells)
    {
      if (setting > 0)
        return setting;
      unsigned int s = 4;
      while (s > 1 && n_cells * std::pow(s, dim) > 8192.)
        --s;
      return s;
    }
  } // namespace discretization
} // namespace igabde

#endif
