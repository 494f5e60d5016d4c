#ifndef igabde_nurbs_nurbs_patch_h
#define igabde_nurbs_nurbs_patch_h

#include <igabde/nurbs/knot_vector.h>

#include <deal.II/base/point.h>
#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <functional>
#include <utility>
#include <vector>

namespace igabde
{
  namespace nurbs
  {
    using namespace dealii;

    /**
     * @brief A single NURBS patch: one open knot vector per parametric
     * direction and a tensor-product net of weighted control points.
     *
     * Control points are numbered lexicographically, direction 0 fastest:
     * A = i + n_0 (j + n_1 k). The parametric domain is the box spanned by
     * the first and last knots of each direction. Faces are numbered as
     * deal.II's colorized boxes: face f lies at the low (f%2 == 0) or high
     * end of direction f/2.
     */
    template <int dim>
    class NurbsPatch
    {
    public:
      /// @brief The dimension (parametric = physical) of the patch.
      static constexpr int dimension = dim;

      /// @brief An empty patch (no knots, no control points).
      NurbsPatch() = default;

      /**
       * @brief Build from knot vectors, control points (lexicographic) and
       * weights; throws with a clear message on inconsistent sizes or a
       * weight <= 0.
       */
      NurbsPatch(const std::array<KnotVector, dim> &knots,
                 const std::vector<Point<dim>>     &control_points,
                 const std::vector<double>         &weights);

      /// Knot vector of direction @p d.
      const KnotVector &
      knot_vector(const unsigned int d) const;

      /// Number of control points in direction @p d.
      unsigned int
      n_control_points(const unsigned int d) const;

      /// Total number of control points.
      unsigned int
      n_control_points() const;

      /// Bytes of the knot vectors, control points and weights.
      double
      memory_consumption() const
      {
        double bytes = double(points.capacity()) * sizeof(Point<dim>) +
                       double(weights.capacity()) * sizeof(double);
        for (const KnotVector &k : knots)
          bytes += double(k.knots().capacity()) * sizeof(double);
        return bytes;
      }

      /// Control point @p a (physical coordinates, not homogeneous).
      const Point<dim> &
      control_point(const unsigned int a) const;

      /// Weight of control point @p a.
      double
      weight(const unsigned int a) const;

      /// Lexicographic index of the control point with tensor index @p ijk.
      unsigned int
      control_point_index(const std::array<unsigned int, dim> &ijk) const;

      /// Physical point x(xi).
      Point<dim>
      value(const Point<dim> &xi) const;

      /**
       * @brief x(xi) at every point of the tensor grid @p coordinates
       * (one list of parametric coordinates per direction), direction 0
       * fastest: the basis functions are evaluated once per coordinate and
       * direction, so a point costs (p+1)^dim multiply-adds instead of a
       * basis evaluation of its own.
       */
      std::vector<Point<dim>>
      values_on_grid(
        const std::array<std::vector<double>, dim> &coordinates) const;

      /// Jacobian dx/dxi at xi (row i: component i, column j: d/dxi_j).
      Tensor<2, dim>
      jacobian(const Point<dim> &xi) const;

      /// Second derivatives d^2 x_c / dxi_i dxi_j at xi, as [c][i][j] (of
      /// the span that basis() takes at xi).
      Tensor<3, dim>
      second_derivatives(const Point<dim> &xi) const;

      /**
       * @brief Nonzero rational basis functions at @p xi: fills the
       * control-point indices, R_A and dR_A/dxi (parametric derivatives).
       */
      void
      basis(const Point<dim>            &xi,
            std::vector<unsigned int>   &indices,
            std::vector<double>         &values,
            std::vector<Tensor<1, dim>> *gradients = nullptr) const;

      /// Unique breakpoints (knot-span boundaries) of direction @p d.
      std::vector<double>
      breakpoints(const unsigned int d) const;

      /// Insert @p n_per_span equally spaced knots into every non-empty span
      /// of every direction (geometry unchanged).
      void
      refine_uniformly(const unsigned int n_per_span = 1);

      /// Insert the knots @p new_knots into direction @p d (Boehm).
      void
      insert_knots(const unsigned int d, const std::vector<double> &new_knots);

      /// Raise the degree of direction @p d by @p t (continuity kept).
      void
      elevate_degree(const unsigned int d, const unsigned int t = 1);

      /**
       * @brief Closest parametric point on the face @p face to the physical
       * point @p x (Newton from a sampled start). Returns xi in the volume
       * parametric coordinates (the face coordinate fixed).
       *
       * The start is the nearest of the images of the breakpoints and three
       * points per span of the face. With @p near (a parametric point of
       * the face near the answer, e.g. the nearest of a set of surface
       * points) only the spans within one span of @p near are sampled; the
       * whole face is sampled after all when the answer found there is
       * farther from @p x than the image of @p near.
       */
      Point<dim>
      closest_point_on_face(const unsigned int face,
                            const Point<dim>  &x,
                            const Point<dim>  *near = nullptr) const;

      /**
       * @brief The centroid of the face @p face (its area-weighted mean
       * point), by Gauss quadrature over the face's knot spans.
       */
      Point<dim>
      face_centroid(const unsigned int face) const;

      /**
       * @brief Outward unit normal of the body at the face @p face at @p xi.
       */
      Tensor<1, dim>
      outward_normal(const unsigned int face, const Point<dim> &xi) const;

      /// @brief Polynomial degree of direction @p d.
      unsigned int
      degree(const unsigned int d) const;

      /// @brief Tensor index (i, j[, k]) of the control point @p a.
      std::array<unsigned int, dim>
      tensor_index(const unsigned int a) const;

      /// @brief Lower corner of the parametric box (first knots).
      Point<dim>
      parametric_lower() const;

      /// @brief Upper corner of the parametric box (last knots).
      Point<dim>
      parametric_upper() const;

      /**
       * @brief Lexicographic indices of the control points on the face
       * @p face (open knot vectors: exactly those with a nonzero trace there),
       * ordered lexicographically in the remaining directions.
       */
      std::vector<unsigned int>
      face_control_points(const unsigned int face) const;

      /**
       * @brief Sign (+1 or -1) of det(dx/dxi) at the centre of the parametric
       * box: +1 for a right-handed parametrization. The builders' curved
       * beam, for instance, is left-handed (-1).
       */
      double
      orientation() const;

      /**
       * @brief Parametric point in the patch's parametric box whose image is
       * closest to @p x (for a point of the body: x(xi) = x). Projected
       * Newton on |x(xi) - x|^2, started from @p start, or when @p start is
       * null from the nearest of the images of the breakpoints and span
       * midpoints. If @p distance is not null it receives |x(xi) - x|.
       */
      Point<dim>
      closest_parametric_point(const Point<dim> &x,
                               const Point<dim> *start    = nullptr,
                               double           *distance = nullptr) const;

      /**
       * @brief Homogeneous control net as a flat list: entry a holds
       * (w_a P_a, w_a).
       */
      std::vector<std::array<double, dim + 1>>
      homogeneous_control_points() const;

    private:
      /// The tensor combination of @p samples whose image is nearest to @p x.
      Point<dim>
      nearest_sample(const std::array<std::vector<double>, dim> &samples,
                     const Point<dim>                           &x) const;

      /**
       * @brief Minimises |x(xi) - x|^2 over the parametric box, keeping the
       * coordinates with @p fixed[d] == true at their start values.
       */
      Point<dim>
      minimize_distance(const Point<dim>            &x,
                        Point<dim>                   xi,
                        const std::array<bool, dim> &fixed,
                        double                      *distance) const;

      /// Replaces direction @p d's knot vector and net from homogeneous
      /// points transformed line by line with the (n_new x n_old) matrix T,
      /// stored by rows as (column, value) pairs.
      void
      transform_direction(
        const unsigned int d,
        const KnotVector  &new_knots,
        const std::vector<std::vector<std::pair<unsigned int, double>>> &T);

      std::array<KnotVector, dim> knots;
      std::vector<Point<dim>>     points;
      std::vector<double>         weights;
      /// The largest distance of a control point from the first: the
      /// physical size of minimize_distance()'s stopping test (kept with the
      /// points, not recomputed per call: a refined patch has 10^5 points).
      double physical_size = 1e-300;

      /// Sets physical_size from the points.
      void
      update_physical_size();
    };

    /**
     * @brief Column @p d of cof(J) = det(J) J^{-T}: the (unnormalised)
     * normal of the surface xi_d = const, pointing towards increasing xi_d
     * when det J > 0. Computed from the tangents, so it stays defined where
     * J is singular in another direction.
     */
    template <int dim>
    Tensor<1, dim>
    cofactor_column(const Tensor<2, dim> &J, const unsigned int d);

    /**
     * @brief Control-point values on the face @p face of @p patch whose
     * NURBS interpolant sum_A R_A v_A matches @p g at the images of the
     * face's Greville points (collocation: exact for g in the face's NURBS
     * space, e.g. constants and, on polynomial patches, the face's
     * polynomials). Ordered as NurbsPatch::face_control_points(). The
     * collocation matrix is diag(1/W) (B_1 x B_2) diag(w) with the 1D
     * B-spline collocation matrices B_k, so it is solved by one 1D LU per
     * face direction, not as a dense system.
     */
    template <int dim>
    std::vector<double>
    interpolate_on_face(const NurbsPatch<dim>                           &patch,
                        const unsigned int                               face,
                        const std::function<double(const Point<dim> &)> &g);

    /**
     * @brief Every tensor combination of the per-direction coordinates
     * @p coords, direction 0 fastest (the lexicographic order of the
     * control points).
     */
    template <int dim>
    std::vector<Point<dim>>
    tensor_product_points(const std::array<std::vector<double>, dim> &coords);
  } // namespace nurbs
} // namespace igabde

#endif
