#ifndef igabde_discretization_surface_point_h
#define igabde_discretization_surface_point_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/vector.h>

#include <array>
#include <string>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /**
     * @brief The linear map from a body's unknowns to the displacement at one
     * point, and its transpose, which distributes a point force to the
     * unknowns (P_A = R_A(xi) P).
     *
     * u_c(X) = sum_k weights[k] u[dofs[k][c]].
     */
    template <int dim>
    struct PointOperator
    {
      /// Basis function values at the point (NURBS R_A or Lagrange N_i).
      std::vector<double> weights;
      /// Vector-valued unknowns of each basis function, per component.
      std::vector<std::array<types::global_dof_index, dim>> dofs;

      /// Displacement at the point for the unknowns @p u.
      Tensor<1, dim>
      displacement(const Vector<double> &u) const;

      /// Adds the point force @p force to the load vector @p f.
      void
      distribute(const Tensor<1, dim> &force, Vector<double> &f) const;
    };

    /**
     * @brief A candidate contact point on a body's surface.
     */
    template <int dim>
    struct SurfacePoint
    {
      /// Physical location (m).
      Point<dim> location;
      /// Volume parametric coordinates (NURBS) or reference location
      /// (Lagrange: the node's position on the parametric mesh).
      Point<dim> parametric;
      /// Outward unit normal of this body at the point.
      Tensor<1, dim> normal;
      /// Share of a uniform pressure carried by the point (m^2, m in 2D).
      double tributary_area = 0.;
      /// Displacement / point-force operator.
      PointOperator<dim> op;
    };

    /**
     * @brief A point of a patch face given by its face coordinates (the
     * patch's parametric coordinates without the face's normal direction,
     * in order): what the weighted-gap pairing integrates with.
     */
    template <int dim>
    struct FacePoint
    {
      /// Physical location (m).
      Point<dim> location;
      /// Outward unit normal of the body.
      Tensor<1, dim> normal;
      /// Surface measure per unit face-coordinate measure: dGamma = measure
      /// deta (m per unit parameter in 2D, m^2 in 3D).
      double measure = 0.;
      /// dx/deta_k (m per unit parameter), one per face coordinate.
      std::array<Tensor<1, dim>, dim - 1> tangents;
      /// Displacement / point-force operator; on the face only the trace
      /// basis (the face's control points or nodes) is non-zero.
      PointOperator<dim> op;
      /// The operator's weights' derivatives by the face coordinates,
      /// gradients[k][a] = d op.weights[k] / deta_a (per unit parameter):
      /// the basis derivatives the tangents are made of, t_a = sum_k
      /// gradients[k][a] x_k.
      std::vector<std::array<double, dim - 1>> gradients;
    };

    /**
     * @brief The tangents' derivatives at a face point by its face
     * coordinates: second[a][b] = d t_a / d eta_b = d^2 x / deta_a deta_b
     * (symmetric in a and b; m per unit parameter squared).
     */
    template <int dim>
    using FaceSecondDerivatives =
      std::array<std::array<Tensor<1, dim>, dim - 1>, dim - 1>;

    /**
     * @brief The element grid of a patch face in its face coordinates.
     */
    template <int dim>
    struct FaceGrid
    {
      /// Element breaks per face coordinate (ascending; the face is the
      /// box from the first to the last break).
      std::array<std::vector<double>, dim - 1> breaks;
      /// Largest degree of the basis in the face coordinates.
      unsigned int degree = 1;
    };

    /**
     * @brief Face @p face of a body of dimension @p dimension as scenes
     * write it: "f" on patch 0, "p.f" on patch p > 0 (the face number is
     * p * 2 dimension + f).
     */
    inline std::string
    face_name(const unsigned int face, const unsigned int dimension)
    {
      return face < 2 * dimension ?
               std::to_string(face) :
               std::to_string(face / (2 * dimension)) + "." +
                 std::to_string(face % (2 * dimension));
    }
  } // namespace discretization
} // namespace igabde

#endif
