#ifndef igabde_discretization_iga_body_h
#define igabde_discretization_iga_body_h

#include <igabde/base/nearest_points.h>

#include <igabde/nurbs/nurbs_patch.h>
#include <igabde/nurbs/nurbs_values.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/grid/tria.h>

#include <Eigen/Dense>

#include <array>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /**
     * @brief The isogeometric (NURBS) discretisation of a body, hosted in
     * deal.II.
     *
     * A body is one patch or several glued at conforming interfaces
     * (BodyDescription::interfaces): every patch below is treated alike and
     * the control points that interface faces share are one unknown
     * (nurbs::glue_control_points()); face p * 2 dim + f is face f of
     * patch p.
     *
     * The description's patch is elevated to settings.degree in every
     * direction whose degree is lower, then h-refined settings.refinements
     * times (one midpoint knot per span and direction each time); the
     * geometry is unchanged by both. The parametric box is a deal.II
     * Triangulation with one cell per non-empty knot span (boundary id =
     * patch face). On a cell the B-splines are the Bernstein polynomials
     * times the 1D Bézier extraction operators, tensorised, and the NURBS
     * functions R = w N / W; the geometry map x = sum R_A P_A and its
     * Jacobian are evaluated by hand (no Mapping). Unknowns are control-point
     * displacements: dof = dim A + c for the lexicographic control point A.
     *
     * Quadrature (p the largest degree): n = p+1 Gauss points per
     * direction in the cells when the weights are all equal (polynomial
     * integrands on affine geometry), n = p+2 when the patch is rational:
     * with p+1 the quadrature error of the rational integrands broke the
     * uniform-stress patch test on the plate with hole at the 1e-7 level,
     * with p+2 it holds to 1e-9. Faces (tractions, tributary areas) use
     * n+1 points, the error norms p+3, and measure() p+1 on polynomial
     * patches (exact) and a high-order rule QGauss(max(p+1, 12)) on
     * rational ones, exact to round-off on the curved test geometries.
     */
    template <int dim>
    class IgaBody : public Body<dim>
    {
    public:
      /**
       * @brief Copies the description, elevates and refines the geometry and
       * builds the parametric mesh; setup() builds the space and assembles.
       */
      IgaBody(const BodyDescription<dim>   &description,
              const DiscretizationSettings &settings);

      /// @brief "nurbs".
      std::string
      discretization_name() const override;

      /// @brief Number of non-empty knot spans over all patches.
      unsigned int
      n_elements() const override;

      double
      mesh_bytes() const override;

      /// @brief Number of patches.
      unsigned int
      n_patches() const override;

      /**
       * @brief R_A at the parametric preimage of @p location (Newton
       * inversion of the map); throws if the point is farther than 1e-8
       * times the body's size from the body.
       */
      PointOperator<dim>
      point_operator(const Point<dim> &location) const override;

      /**
       * @brief Points on the patch face @p face: images of the Greville
       * abscissae of the face's directions (as many as the face's control
       * points), of the knot grid, or the face's Gauss points (QGauss(p+1)
       * per span and direction).
       *
       * Tributary areas A_i solve sum_i R_A(xi_i) A_i = int_face R_A dGamma
       * for the face's control points A: exactly (square system) for
       * Greville points; in the least-squares sense for knot points (more
       * control points than knot points when p >= 2, so a uniform pressure
       * is reproduced only approximately); for Gauss points the quadrature
       * weights times the surface measure are used, which solve the
       * (underdetermined) system up to quadrature error.
       */
      std::vector<SurfacePoint<dim>>
      surface_points(const types::boundary_id face,
                     const PairPlacement      placement) const;

      /// @brief surface_points() with the placement of the settings.
      std::vector<SurfacePoint<dim>>
      surface_points(const types::boundary_id face) const override;

      /// @brief The face's knot spans in its parametric coordinates.
      FaceGrid<dim>
      face_grid(const types::boundary_id face) const override;

      /// @brief The exact NURBS face at the parametric point @p eta.
      FacePoint<dim>
      face_point(const types::boundary_id face,
                 const Point<dim - 1>    &eta) const override;

      /// @brief The NURBS face's second derivatives at @p eta.
      FaceSecondDerivatives<dim>
      face_second_derivatives(const types::boundary_id face,
                              const Point<dim - 1>    &eta) const override;

      /**
       * @brief Relative L2 error of the displacement and relative energy
       * error sqrt(int (s - s_h) : C^-1 : (s - s_h) / int s : C^-1 : s);
       * energy_relative is NaN when @p exact has no stress.
       */
      ErrorNorms
      compute_errors(const Vector<double>     &u,
                     const ExactSolution<dim> &exact) const override;

      /// @brief Stress sigma = C : eps(u_h) at a physical point of the body.
      SymmetricTensor<2, dim>
      stress(const Vector<double> &u,
             const Point<dim>     &location) const override;

      Tensor<2, dim>
      displacement_gradient(const Vector<double> &u,
                            const Point<dim>     &location) const override;

      /**
       * @brief VTU with one patch per knot span, settings.output_subdivisions
       * subdivisions, vertices at the exact x(xi): displacement (vector),
       * strain and stress components, von Mises stress (with the
       * out-of-plane stress of plane strain in 2D).
       */
      void
      write_vtu(const Vector<double> &u,
                const std::string    &filename,
                const unsigned int    piece,
                const unsigned int    n_pieces) const override;

      void
      write_pvtu_record(
        const std::string              &filename,
        const std::vector<std::string> &piece_files) const override;

      /// @brief Area (2D) or volume (3D), see the class note on quadrature.
      double
      measure() const override;

      const nurbs::NurbsPatch<dim> &
      geometry_patch(const unsigned int p = 0) const override
      {
        return spaces.at(p).geometry;
      }

      std::pair<double, Point<dim>>
      largest_strain(const Vector<double> &u) const override;

      double
      internal_force(const Vector<double>                        &u,
                     const elasticity::HyperelasticMaterial<dim> &material,
                     Vector<double>                              &force,
                     SparseMatrix<double> *tangent) const override;

      void
      add_follower_pressure(const Vector<double>      &u,
                            const std::vector<double> &factors,
                            Vector<double>            &residual,
                            SparseMatrix<double>      *tangent) const override;

      /// @brief The refined and elevated patch @p p: its analysis space.
      const nurbs::NurbsPatch<dim> &
      patch(const unsigned int p = 0) const;

      /// @brief The parametric mesh of patch @p p (one cell per non-empty
      /// knot span).
      const Triangulation<dim> &
      triangulation(const unsigned int p = 0) const;

      /// @brief The glued index of each control point of patch @p p (its
      /// unknowns are dim n + c).
      const std::vector<unsigned int> &
      control_point_numbers(const unsigned int p) const;

      /**
       * @brief Parametric coordinates of a physical point of the body
       * (Newton inversion from the nearest sampled point); throws with the
       * distance if the point is not in the body (tolerance 1e-8 times the
       * body's size).
       */
      Point<dim>
      parametric_point(const Point<dim> &location) const;

      /// @brief parametric_point() with the patch that holds the point (of
      /// a point on an interface, either).
      std::pair<unsigned int, Point<dim>>
      locate(const Point<dim> &location) const;

      /**
       * @brief The exact closest point of the NURBS face @p face to
       * @p location (Newton on the patch), with the exact outward normal.
       */
      SurfacePoint<dim>
      closest_surface_point(const types::boundary_id face,
                            const Point<dim>        &location,
                            const SurfacePoint<dim> &nearest) const override;

      /// @brief Displacement/point-force operator at parametric point @p xi
      /// of patch @p p.
      PointOperator<dim>
      parametric_point_operator(const Point<dim>  &xi,
                                const unsigned int p = 0) const;

      /**
       * @brief Strain eps(u_h) at the parametric point @p xi; at a point
       * where the map is singular (the plate's double corner, the Hertz
       * disc's 45-degree corner) the limit from inside the patch.
       */
      SymmetricTensor<2, dim>
      strain_at_parametric(const Vector<double> &u,
                           const Point<dim>     &xi,
                           const unsigned int    p = 0) const;

      /// grad u_h at the parametric point @p xi of patch @p p (the limit
      /// from inside where the map is singular, as strain_at_parametric()).
      Tensor<2, dim>
      gradient_at_parametric(const Vector<double> &u,
                             const Point<dim>     &xi,
                             const unsigned int    p) const;

      /// The body's control-point numbers of the basis functions of patch
      /// @p p at @p xi (a regular_point()) and their physical gradients.
      std::pair<std::vector<unsigned int>, std::vector<Tensor<1, dim>>>
      basis_gradients(const Point<dim> &xi, const unsigned int p) const;

      /// The point a short step from @p xi towards the centre of patch
      /// @p p where the map is regular (|det J| >= 1e-3 |J|^dim), and J
      /// there; @p xi itself where it is regular already.
      std::pair<Point<dim>, Tensor<2, dim>>
      regular_point(const Point<dim> &xi, const unsigned int p) const;

      /// @brief Gauss points per direction of the cell rule (p+1, or p+2
      /// for a rational patch); faces use one more.
      unsigned int
      n_quadrature_points_1d() const;

      /// @brief Displacement u_h at the parametric point @p xi.
      Tensor<1, dim>
      displacement_at_parametric(const Vector<double> &u,
                                 const Point<dim>     &xi,
                                 const unsigned int    p = 0) const;

    protected:
      /// @brief Per patch, a copy of its geometry with the control points
      /// moved by the displacement (nullptr: none).
      void
      move_surface_geometry(const Vector<double> *u) const override;

      /// @brief Unknowns, control-point locations, supports and sparsity.
      void
      setup_space() override;

      /// @brief Stiffness and loads with WorkStream (all cores).
      void
      assemble() override;

    private:
      /// The unknowns of @p op for the control points @p indices of patch
      /// @p p (their glued numbers, every component).
      void
      number_operator(const std::vector<unsigned int> &indices,
                      const unsigned int               p,
                      PointOperator<dim>              &op) const;

      /// One patch of the body: its analysis space and parametric mesh.
      struct PatchSpace
      {
        /// The elevated and refined patch.
        nurbs::NurbsPatch<dim> geometry;
        /// One cell per non-empty knot span (boundary id = patch face).
        Triangulation<dim> mesh;
        /// Knot breakpoints per direction.
        std::array<std::vector<double>, dim> breaks;
        /// Sign of det(dx/dxi) (+1 right-handed).
        double orientation = 1.;
        /// The glued index of each control point.
        std::vector<unsigned int> numbers;
        /// Newton starts of the point inversion: their coordinates per
        /// direction (a tensor grid, direction 0 fastest).
        std::array<std::vector<double>, dim> sample_coordinates;
      };

      /// The surface queries' geometry of @p space: the patch itself, or
      /// its moved copy after Body::move_surfaces().
      const nurbs::NurbsPatch<dim> &
      surface_geometry(const PatchSpace &space) const;

      /// Per patch, the geometry with moved control points
      /// (move_surface_geometry(); empty on the reference configuration).
      mutable std::vector<nurbs::NurbsPatch<dim>> moved_geometry;

      /// Surface measure factor |cof(J) e_d| and outward unit normal of the
      /// patch face @p face (0..2 dim - 1) of a patch of orientation
      /// @p orientation.
      static std::pair<double, Tensor<1, dim>>
      face_measure_and_normal(const unsigned int    face,
                              const Tensor<2, dim> &J,
                              const double          orientation);

      /// The patch and its face (0..2 dim - 1) of the body face @p face;
      /// throws naming the body when there is no such face.
      std::pair<const PatchSpace *, unsigned int>
      patch_face(const types::boundary_id face) const;

      /// Tributary areas of the Greville points of face @p face of
      /// @p space: the collocation system sum_i R_A(xi_i) A_i = @p integrals
      /// (one entry per control point of @p face_cps), solved direction by
      /// direction.
      Eigen::VectorXd
      greville_tributary_areas(const PatchSpace                &space,
                               const unsigned int               face,
                               const std::vector<unsigned int> &face_cps,
                               const Eigen::VectorXd &integrals) const;

      /// Largest degree over the directions and patches.
      unsigned int
      max_degree() const;

      /// The patches (sized once in the constructor: a Triangulation is not
      /// moved).
      std::vector<PatchSpace> spaces;
      /// Number of glued control points (n_unknowns / dim).
      unsigned int n_points = 0;
      /// Pair placement parsed from the settings.
      PairPlacement default_placement = PairPlacement::greville;
      /// Size of the body (bounding-box diagonal of the control nets).
      double diameter = 0.;
      /// The samples' images per patch, indexed by R-trees built at the
      /// first inversion (most runs invert no point; V5 with 4 refinements
      /// has a million samples and inverts a thousand pair points, which a
      /// scan took a second for).
      mutable std::once_flag index_built;
      mutable std::vector<std::unique_ptr<base::NearestPoints<dim>>>
        sample_index;
    };
  } // namespace discretization
} // namespace igabde

#endif
