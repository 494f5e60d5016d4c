#ifndef igabde_discretization_lagrange_body_h
#define igabde_discretization_lagrange_body_h

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe_field.h>

#include <array>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /**
     * @brief The Lagrange comparison path: FE_Q(k)^dim on the knot-span
     * mesh of the body's NURBS patch, with the geometry interpolated from the
     * exact NURBS map at the FE_Q support points (isoparametric
     * MappingFEField), so curved boundaries are curved elements of degree k.
     * A body of several patches is meshed patch by patch, the vertices of
     * their conforming interfaces shared (one continuous FE_Q space), face
     * f of patch p having boundary id p * 2 dim + f.
     */
    template <int dim>
    class LagrangeBody : public Body<dim>
    {
    public:
      /// Builds nothing yet; setup() does the work.
      LagrangeBody(const BodyDescription<dim>   &description,
                   const DiscretizationSettings &settings);

      std::string
      discretization_name() const override;

      unsigned int
      n_elements() const override;

      double
      mesh_bytes() const override;

      PointOperator<dim>
      point_operator(const Point<dim> &location) const override;

      std::vector<SurfacePoint<dim>>
      surface_points(const types::boundary_id face) const override;

      /**
       * @brief The face's cells: the knot spans of the patch the mesh was
       * made from, in the patch's parametric coordinates.
       */
      FaceGrid<dim>
      face_grid(const types::boundary_id face) const override;

      /**
       * @brief The isoparametric face at @p eta: the cell holding the
       * parametric point, FE_Q values there, the mapped location and the
       * normal from the mapped Jacobian.
       */
      FacePoint<dim>
      face_point(const types::boundary_id face,
                 const Point<dim - 1>    &eta) const override;

      /// @brief The cell's mapped second derivatives at @p eta.
      FaceSecondDerivatives<dim>
      face_second_derivatives(const types::boundary_id face,
                              const Point<dim - 1>    &eta) const override;

      ErrorNorms
      compute_errors(const Vector<double>     &u,
                     const ExactSolution<dim> &exact) const override;

      SymmetricTensor<2, dim>
      stress(const Vector<double> &u,
             const Point<dim>     &location) const override;

      Tensor<2, dim>
      displacement_gradient(const Vector<double> &u,
                            const Point<dim>     &location) const override;

      void
      write_vtu(const Vector<double> &u,
                const std::string    &filename,
                const unsigned int    piece,
                const unsigned int    n_pieces) const override;

      void
      write_pvtu_record(
        const std::string              &filename,
        const std::vector<std::string> &piece_files) const override;

      double
      measure() const override;

      const nurbs::NurbsPatch<dim> &
      geometry_patch(const unsigned int p = 0) const override
      {
        return patches.at(p);
      }

      unsigned int
      n_patches() const override
      {
        return patches.size();
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

      /**
       * @brief The smallest ratio det J(p) / |det J(centre)| of the cell maps
       * over the points @p unit_points of the unit cell and all cells, and
       * the centre of the cell where it occurs. Positive exactly when no
       * cell is inverted at those points (a valid geometry); setup() checks
       * it at the quadrature and output points.
       */
      std::pair<double, Point<dim>>
      min_jacobian_ratio(const std::vector<Point<dim>> &unit_points) const;

    protected:
      /// A second mapping on the support points moved by the displacement
      /// (nullptr: none).
      void
      move_surface_geometry(const Vector<double> *u) const override;

      void
      setup_space() override;

      void
      assemble() override;

    private:
      /**
       * The parametric box of a cell: the patch, and the map from the unit
       * cell, xi[direction[e]] = origin[direction[e]] + unit[e] length[e]
       * (a length is negative where the cell runs its direction backwards).
       */
      struct CellParameters
      {
        unsigned int                  patch = 0;
        Point<dim>                    origin;
        std::array<unsigned int, dim> direction{};
        std::array<double, dim>       length{};
      };

      /// The mesh: one patch's parametric mesh, or several patches' laid
      /// out in space with the vertices of their interfaces shared; fills
      /// cell_parameters and the boundary ids (faces p 2 dim + f).
      void
      make_mesh();

      /// The patch of @p cell.
      unsigned int
      patch_of(const typename Triangulation<dim>::cell_iterator &cell) const;

      /// The patch's parametric point of the unit-cell point @p unit of
      /// @p cell.
      Point<dim>
      parametric_point(const typename Triangulation<dim>::cell_iterator &cell,
                       const Point<dim> &unit) const;

      /// (0.5, ..., 0.5).
      static Point<dim>
      unit_centre();

      /// The patches after the scene's h-refinements (the map the cells
      /// follow).
      std::vector<nurbs::NurbsPatch<dim>> patches;
      /// Per active cell.
      std::vector<CellParameters> cell_parameters;
      Triangulation<dim>          triangulation;
      FESystem<dim>               fe;
      DoFHandler<dim>             dof_handler;
      /// Physical position of every support point (the MappingFEField data).
      Vector<double>                            euler_vector;
      std::unique_ptr<MappingFEField<dim, dim>> mapping;
      /// The support points moved by Body::move_surfaces() and their
      /// mapping (empty on the reference configuration); what the surface
      /// queries use, surface_geometry() and surface_mapping().
      mutable Vector<double>                            moved_euler_vector;
      mutable std::unique_ptr<MappingFEField<dim, dim>> moved_mapping;
      const Vector<double> &
      surface_geometry() const
      {
        return this->surfaces_moved() && moved_mapping ? moved_euler_vector :
                                                         euler_vector;
      }
      const Mapping<dim> &
      surface_mapping() const
      {
        return this->surfaces_moved() && moved_mapping ? *moved_mapping :
                                                         *mapping;
      }
      /// Point location (GridTools::Cache on the mapping), built on first
      /// use by find_cell().
      mutable std::unique_ptr<GridTools::Cache<dim>> cache;
      mutable std::mutex                             cache_mutex;

      /// The cell holding @p location and the point's unit coordinates in
      /// it; throws for a point outside the body. Thread-safe: the cache's
      /// own data fill lazily, so each search holds the lock (the output's
      /// recovered pressures search in a background thread).
      std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>
      find_cell(const Point<dim> &location) const;
      /// Every cell holding @p location within @p tolerance in unit
      /// coordinates, with the point's unit coordinates in it, nearest first
      /// (the nearest alone when none is that close); throws as
      /// find_cell().
      std::vector<
        std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>>
      find_cells(const Point<dim> &location, const double tolerance) const;

      /**
       * @brief The mean of @p value(values, local_u) over the cells that
       * hold @p location (within 1e-8 in unit coordinates), each evaluated
       * at the point's unit coordinates in it: the FE_Q gradient jumps
       * across cells, so that on a face, edge or vertex the result does not
       * depend on which cell a search meets first.
       */
      template <typename Value>
      auto
      mean_over_cells(const Vector<double> &u,
                      const Point<dim>     &location,
                      const Value          &value) const;
      /// The cell of patch face @p body_face that holds the face
      /// coordinates @p eta, and the point's unit coordinates in it (on the
      /// face exactly).
      std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>
      face_cell(const types::boundary_id body_face,
                const Point<dim - 1>    &eta) const;
      /// The cell of each knot span, per patch (face_point()).
      std::vector<std::map<std::array<unsigned int, dim>,
                           typename DoFHandler<dim>::active_cell_iterator>>
        cell_of_span;
    };
  } // namespace discretization
} // namespace igabde

#endif
