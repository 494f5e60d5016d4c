#ifndef igabde_discretization_body_h
#define igabde_discretization_body_h

#include <igabde/base/memory_record.h>

#include <igabde/discretization/rigid_modes.h>
#include <igabde/discretization/settings.h>
#include <igabde/discretization/surface_point.h>

#include <igabde/elasticity/body_force.h>
#include <igabde/elasticity/error_norms.h>
#include <igabde/elasticity/hyperelastic.h>
#include <igabde/elasticity/material.h>

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <map>
#include <memory>
#include <mpi.h>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace igabde
{
  namespace nurbs
  {
    // Only the reference geometry_patch() returns: the contact layer,
    // which sees bodies through this header, stays free of nurbs/.
    template <int dim>
    class NurbsPatch;
  } // namespace nurbs

  namespace discretization
  {
    /**
     * @brief Where a body's direct factorisation runs under MPI.
     *
     * Every rank of @p world holds the body (its space, matrix and fields);
     * the ranks of @p group factorise it together (MUMPS on that
     * communicator, the group's first rank holding the matrix and the
     * Schur complement), and hand what the others need (the factor of the
     * Schur complement, the external solutions, every solve's result) over
     * @p world from @p root, the group's first rank. The default is one
     * process doing everything.
     */
    struct ParallelLayout
    {
      /// Every rank that uses the body.
      MPI_Comm world = MPI_COMM_SELF;
      /// The ranks that factorise it; MPI_COMM_NULL on the others.
      MPI_Comm group = MPI_COMM_SELF;
      /// Rank in @p world of the group's first rank.
      unsigned int root = 0;
      /// Whether every rank assembles K (false: only the group does, and
      /// the others receive the load vectors; ensure_assembled() builds K
      /// where it is needed after all).
      bool matrix_everywhere = true;
    };

    using namespace dealii;

    template <int dim>
    struct BodyDescription;
    template <int dim>
    struct NeumannCondition;
    template <int dim>
    struct PointLoad;

    /// Exact solution of a verification scene (elasticity room).
    template <int dim>
    using ExactSolution = elasticity::ExactSolution<dim>;

    /// Relative error norms (elasticity room).
    using ErrorNorms = elasticity::ErrorNorms;

    /**
     * @brief A deformable body, discretised by NURBS or by Lagrange elements.
     *
     * This is the small interface the contact layer and the simulator see:
     * give the displacement at points, apply point forces, solve for many
     * right-hand sides. The linear algebra common to both discretisations
     * (constraints, factorisation, superposition of load cases, rigid modes
     * left free by the supports) lives here; a derived class builds the space
     * and assembles.
     */
    template <int dim>
    class Body
    {
    public:
      /**
       * @brief Keeps the description and the discretisation settings.
       */
      Body(const BodyDescription<dim>   &description,
           const DiscretizationSettings &settings);

      virtual ~Body();

      /**
       * @brief Builds the space, assembles K and the load vector, applies
       * supports, detects free rigid modes and factorises: setup_system()
       * followed by factorize() without interface.
       */
      void
      setup();

      /**
       * @brief Builds the space, assembles K and the load vector, applies
       * supports and detects free rigid modes; no factorisation yet.
       */
      void
      setup_system();

      /**
       * @brief Factorises K and solves the two load cases (loads and
       * prescribed displacements at factor 1).
       *
       * With the direct solver and a non-empty @p interface (the operators
       * of the contact points on this body), the factorisation also forms
       * the Schur complement of K onto the unknowns those operators touch,
       * so that flexibility() costs a dense solve on the contact face
       * instead of one sparse solve per column.
       *
       * With @p keep_reaction_rows, K keeps only the rows the support
       * reactions read (keep_reaction_rows_only()) from the moment the
       * factorisation has read it, before the numerical factorisation:
       * the path that reads K no more afterwards (the condensed one,
       * or no contact) frees the rest where the memory peaks.
       */
      void
      factorize(const std::vector<PointOperator<dim>> &interface = {},
                bool keep_reaction_rows                          = false);

      /**
       * @brief Sets where the assembly and the factorisation run (before
       * setup_system()). factorize() is then collective on the layout's
       * group (a rank outside it only frees K's pattern when K is read no
       * more: @p keep_reaction_rows), share_assembly(),
       * share_factorization(), solve() and support_reaction() on its world.
       */
      void
      set_parallel_layout(const ParallelLayout &layout);

      /// Where the assembly and the factorisation run.
      const ParallelLayout &
      parallel_layout() const
      {
        return layout;
      }

      /**
       * @brief After setup_system() on every rank: the ranks that did not
       * assemble K receive the load vectors and the matrix's size from the
       * layout's root (collective on the world; nothing to do in one
       * process).
       */
      void
      share_assembly();

      /// Assembles K on this rank if setup_system() left it out.
      void
      ensure_assembled();

      /// Entries of K's sparsity pattern (also where K was not assembled).
      std::size_t
      n_matrix_entries() const;

      /// Whether this rank factorises the body (always in one process).
      bool
      factorizes_here() const;

      /**
       * @brief After factorize() on the group: every rank of the world gets
       * the external solutions and, with a Schur complement, its factor
       * (collective on the world; nothing to do in one process).
       */
      void
      share_factorization();

      /**
       * @brief Frees the factorisation (MUMPS' factor and its copy of K, S;
       * UMFPACK's LU; the AMG hierarchy) once the load cases are solved
       * and no more solves will come: the full contact path factorises
       * the coupled system itself and reads the external solutions only.
       * The factor's size and flops stay for reports. Collective on the
       * layout's world.
       */
      void
      release_factorization();

      /**
       * @brief Keeps of K only the rows the support reactions read (the
       * supported and prescribed unknowns), once the direct solver has
       * factorised it and the load cases are solved: on the condensed
       * path nothing else reads K afterwards (doc/performance.md, "Peak
       * memory"). Not for the full path, whose coupled system reads the whole
       * K, nor for the umfpack and cg-amg solvers, whose copies of K share
       * its sparsity pattern.
       */
      void
      keep_reaction_rows_only();

      /**
       * @brief Where solves one column after the other (CG with AMG, which
       * may take minutes for the contact columns) report how far they are:
       * a line at every tenth of at least 100 columns. nullptr (the
       * default, and on every rank but the one that prints) stays silent.
       */
      void
      set_progress_stream(std::ostream *stream);

      /**
       * @brief The flexibility of point-force patterns:
       * F(i, j) = d_i . u_j(x_i), where u_j solves K u_j = f_j for the unit
       * force @p directions[j] at the point of @p operators[j] (with the
       * pins of free rigid modes: K^+). Symmetric. From the Schur
       * complement when factorize() formed one on the unknowns the
       * operators touch, else one solve per column.
       */
      FullMatrix<double>
      flexibility(const std::vector<PointOperator<dim>> &operators,
                  const std::vector<Tensor<1, dim>>     &directions) const;

      /**
       * @brief flexibility() in two halves, so that the bodies' groups
       * compute theirs at the same time: flexibility_in_group() on the
       * ranks that factorise the body (collective on the layout's group;
       * the result is on the layout's root, empty elsewhere), then
       * share_flexibility() on every rank (collective on the world).
       */
      FullMatrix<double>
      flexibility_in_group(const std::vector<PointOperator<dim>> &operators,
                           const std::vector<Tensor<1, dim>> &directions) const;

      /// Second half of flexibility(): @p F from the layout's root to all.
      void
      share_flexibility(FullMatrix<double> &F) const;

      /**
       * @brief The assembled stiffness K, before supports are applied (the
       * full-system contact path assembles it into the coupled matrix).
       */
      const SparseMatrix<double> &
      stiffness_matrix() const;

      /**
       * @brief Whether unknown @p i is held at zero in every solve of the
       * contact correction: a support, or a pin that removes a free rigid
       * mode (its rigid motion then enters through the mode amplitudes).
       */
      bool
      is_held(const types::global_dof_index i) const;

      /**
       * @brief Whether unknown @p i is held by a support (not by a pin of a
       * free rigid mode, which moves with that mode).
       */
      bool
      is_supported(const types::global_dof_index i) const;

      /// Whether flexibility() uses a Schur complement.
      bool
      has_schur_complement() const;

      /// Unknowns in the Schur complement (0 without).
      unsigned int
      n_interface_dofs() const;

      /// Entries of the sparse factor (direct solver; 0 otherwise).
      double
      factor_entries() const;

      /**
       * Floating-point operations of the sparse factorisation (MUMPS'
       * count, RINFOG(3)) on the ranks that factorised this body; 0
       * elsewhere and without the direct solver.
       */
      double
      factor_flops() const;

      /// "nurbs" or "lagrange".
      virtual std::string
      discretization_name() const = 0;

      /// Number of displacement unknowns.
      types::global_dof_index
      n_dofs() const;

      /// Number of elements (knot spans or cells).
      virtual unsigned int
      n_elements() const = 0;

      /**
       * @brief What this rank holds for the body, by kind ("NAME: mesh",
       * "NAME: unknowns' tables", "NAME: sparsity pattern", "NAME: stiffness
       * matrix", "NAME: load vectors and solutions", "NAME: factorisation"),
       * from the sizes of the data structures' allocations, and whether the
       * ranks divide it (base::MemoryItem). Not collective.
       */
      std::vector<base::MemoryItem>
      memory_record() const;

      /// Bytes of the mesh and the geometry (the patches' knot-span
      /// meshes and control nets, or the triangulation, the DoF handler and
      /// the geometry field): the "mesh" of memory_record().
      virtual double
      mesh_bytes() const = 0;

      /// The body's description (include body_description.h to use it).
      const BodyDescription<dim> &
      description() const;

      /// The body's name (output files and messages).
      const std::string &
      name() const;

      /// The body's material constants (Hooke's law at small strain).
      const elasticity::IsotropicMaterial<dim> &
      material() const;

      /// Whether the body is modelled at finite strain
      /// (BodyDescription::kinematics).
      bool
      finite_strain() const;

      /// The body's finite-strain law (finite_strain() bodies only).
      elasticity::HyperelasticMaterial<dim>
      finite_law() const;

      /**
       * @brief Operator for a physical point inside or on the body.
       */
      virtual PointOperator<dim>
      point_operator(const Point<dim> &location) const = 0;

      /**
       * @brief Whether @p location lies in the body (to round-off of its
       * size): point_operator() succeeds there.
       */
      virtual bool
      contains(const Point<dim> &location) const;

      /// Displacement component of unknown @p i.
      unsigned int
      dof_component(const types::global_dof_index i) const;

      /// Control point (NURBS) or node (Lagrange) of unknown @p i.
      const Point<dim> &
      dof_location(const types::global_dof_index i) const;

      /**
       * @brief Resultant of the support reactions: the sum over the
       * supported unknowns of (K u - f)_i per component, for the
       * displacement @p u under the applied loads @p f (external loads at
       * their factor plus contact forces). With the supports in
       * equilibrium with f it is minus the resultant of f; the sum is
       * computed from K u, independently of it.
       */
      Tensor<1, dim>
      support_reaction(const Vector<double> &u, const Vector<double> &f) const;

      /**
       * @brief The reaction of the face motion @p k
       * (BodyDescription::face_motions[k]) at the history factors
       * @p factors: the force (dim components) and then the moment about
       * the face's centroid (z in 2D; x, y, z in 3D; at finite strain the
       * centroid moved with the face) that the kinematic coupling applies
       * to the body, from (restoring_force(u) - f)_i over the unknowns its
       * support prescribes, each acting at its control point or node (at
       * finite strain where it has moved; for a rigid virtual motion these
       * are the work-conjugate points, exactly). An unknown the motion
       * shares with a support of a neighbouring face counts for both.
       */
      std::vector<double>
      face_motion_reaction(const Vector<double>      &u,
                           const Vector<double>      &f,
                           const unsigned int         k,
                           const std::vector<double> &factors) const;

      /**
       * @brief The force the body's stress exerts on its unknowns at the
       * displacement @p u, whose difference from the loads is the support
       * reaction: K u at small strain, f_int(u) at finite strain.
       */
      Vector<double>
      restoring_force(const Vector<double> &u) const;

      /**
       * @brief The stress at a physical point of the reference
       * configuration: stress() at small strain, the Cauchy stress of
       * finite_law() at finite strain.
       */
      SymmetricTensor<2, dim>
      point_stress(const Vector<double> &u, const Point<dim> &location) const;

      /**
       * @brief Candidate contact points on the patch face @p face, placed as
       * DiscretizationSettings::pair_placement says (NURBS) or at the face
       * nodes (Lagrange).
       */
      virtual std::vector<SurfacePoint<dim>>
      surface_points(const types::boundary_id face) const = 0;

      /**
       * @brief The point of the patch face @p face closest to @p location,
       * with its outward normal and operator (tributary area 0): the facing
       * point of a pair on non-matching surfaces. @p nearest is the
       * face's candidate point nearest to @p location (from
       * surface_points()). The default projects @p location on the tangent
       * plane at @p nearest; a discretisation with an exact surface
       * overrides it.
       */
      virtual SurfacePoint<dim>
      closest_surface_point(const types::boundary_id face,
                            const Point<dim>        &location,
                            const SurfacePoint<dim> &nearest) const;

      /**
       * @brief The element grid of the patch face @p face in its face
       * coordinates (knot spans of the face, or the face's cells).
       */
      virtual FaceGrid<dim>
      face_grid(const types::boundary_id face) const = 0;

      /**
       * @brief The point of the patch face @p face at face coordinates
       * @p eta (inside the box of face_grid()): location, outward normal,
       * surface measure, tangents, operator and its derivatives by the
       * face coordinates.
       */
      virtual FacePoint<dim>
      face_point(const types::boundary_id face,
                 const Point<dim - 1>    &eta) const = 0;

      /**
       * @brief The tangents' derivatives by the face coordinates at the
       * point face_point() gives (the second derivatives of the face's
       * map), on the same configuration: what the motion of a closest
       * point on a curved face needs (finite sliding's tangent).
       */
      virtual FaceSecondDerivatives<dim>
      face_second_derivatives(const types::boundary_id face,
                              const Point<dim - 1>    &eta) const = 0;

      /**
       * @brief The surface queries on the configuration x = X + @p u (the
       * body's displacement @p u, all unknowns) instead of the reference
       * one, until reset_surfaces(): surface_points(), face_point() and
       * closest_surface_point() then give the current locations, outward
       * normals, tangents, surface measures and tributary areas, for the
       * same material points (the operators do not change; face_grid()
       * neither, it is in face coordinates). NURBS: the patch with its
       * control points moved by @p u, exact as the reference one
       * (isoparametric: x = sum R_A (X_A + u_A)); Lagrange: the elements
       * with their nodes moved. What contact pairing at finite sliding
       * (Contact/Sliding = finite) forms its pairs on. The moved
       * configuration is the calling thread's: other threads (the
       * background writer's recovered pressures) keep querying the
       * reference one meanwhile, and never read the moved geometry.
       */
      void
      move_surfaces(const Vector<double> &u) const;

      /// The surface queries on the reference configuration again.
      void
      reset_surfaces() const;

      /// Whether move_surfaces() is in effect for the calling thread.
      bool
      surfaces_moved() const;

      /**
       * @brief Solves K u = f for every column, with homogeneous supports
       * (and the pins that remove free rigid modes); one factorisation serves
       * all. On return each vector holds its solution. Under a
       * ParallelLayout collective on its world: the group solves the root's
       * vectors and every rank receives the solutions.
       */
      void
      solve(std::vector<Vector<double>> &rhs_and_solutions) const;

      /// Displacement under the external loads at load factor 1.
      const Vector<double> &
      load_solution() const;

      /// Displacement under the prescribed displacements at factor 1.
      const Vector<double> &
      prescribed_solution() const;

      /// External load vector at load factor 1 (homogeneous supports).
      const Vector<double> &
      load_vector() const;

      /**
       * @brief Number of load histories (BodyDescription::n_histories()):
       * 0 the load factors, 1 the displacement factors, 2.. named ones.
       */
      unsigned int
      n_histories() const;

      /// Displacement under the loads and prescribed displacements of load
      /// history @p h at factor 1.
      const Vector<double> &
      history_solution(const unsigned int h) const;

      /// External load vector of load history @p h at factor 1.
      const Vector<double> &
      history_load_vector(const unsigned int h) const;

      /**
       * @brief Displacement under the external loads and prescribed
       * displacements at the history factors @p factors (one per
       * history; missing ones count as 0).
       */
      Vector<double>
      external_solution(const std::vector<double> &factors) const;

      /// External load vector at the history factors @p factors.
      Vector<double>
      external_load_vector(const std::vector<double> &factors) const;

      /**
       * @brief Rigid modes (as unknown vectors) that the supports leave free;
       * empty when the body is fixed. Such a body is held only by contact.
       */
      const std::vector<Vector<double>> &
      free_rigid_modes() const;

      /// Human-readable names of the free rigid modes ("translation y", ...).
      const std::vector<std::string> &
      free_rigid_mode_names() const;

      /**
       * @brief Whether the translation along coordinate @p c is among the
       * free rigid modes. The body's contact resultant along @p c then
       * balances its load by the equilibrium of a body held there by
       * contact alone: it is not a result of the solve.
       */
      bool
      free_translation(const unsigned int c) const;

      /**
       * @brief Names of the rigid modes held by BodyDescription's
       * hold_rotation_face (removed from free_rigid_modes(); empty when
       * nothing is held or the supports hold those rotations already).
       */
      const std::vector<std::string> &
      held_rigid_mode_names() const;

      /**
       * @brief The reaction of the held rotations to the loads @p f (all
       * loads on the body, contact forces included): the moment (about z
       * in 2D, x y z in 3D) that the hold applies, as a linear traction on
       * its face, so that the body is balanced in the held modes.
       */
      std::vector<double>
      held_moment(const Vector<double> &f) const;

      /**
       * @brief Relative L2 and energy errors against @p exact.
       */
      virtual ErrorNorms
      compute_errors(const Vector<double>     &u,
                     const ExactSolution<dim> &exact) const = 0;

      /**
       * @brief Stress at a physical point.
       */
      virtual SymmetricTensor<2, dim>
      stress(const Vector<double> &u, const Point<dim> &location) const = 0;

      /**
       * @brief The displacement gradient grad u (with respect to the
       * reference configuration) at a physical point of the reference
       * configuration.
       */
      virtual Tensor<2, dim>
      displacement_gradient(const Vector<double> &u,
                            const Point<dim>     &location) const = 0;

      /**
       * @brief Writes displacement, strain, stress and von Mises on the exact
       * geometry to @p filename (VTU): the cells output_cells(@p piece,
       * @p n_pieces) (all of them for one piece), so that ranks can write
       * one piece each of a parallel VTU (write_pvtu_record()).
       */
      virtual void
      write_vtu(const Vector<double> &u,
                const std::string    &filename,
                const unsigned int    piece,
                const unsigned int    n_pieces) const = 0;

      /**
       * @brief Writes the .pvtu record @p filename that names the pieces
       * @p piece_files written by write_vtu() (their fields, no data).
       */
      virtual void
      write_pvtu_record(const std::string              &filename,
                        const std::vector<std::string> &piece_files) const = 0;

      /**
       * @brief The active cells, in their order, that piece @p piece of
       * @p n_pieces writes: [first, end), the counts equal within one.
       */
      std::pair<unsigned int, unsigned int>
      output_cells(const unsigned int piece, const unsigned int n_pieces) const
      {
        const std::uint64_t n = n_elements();
        return {static_cast<unsigned int>(n * piece / n_pieces),
                static_cast<unsigned int>(n * (piece + 1) / n_pieces)};
      }

      /**
       * @brief The largest principal strain in magnitude at the quadrature
       * points, and where (the small-strain model's range check).
       */
      virtual std::pair<double, Point<dim>>
      largest_strain(const Vector<double> &u) const = 0;

      /// Body area (2D) or volume (3D) by the body's quadrature.
      virtual double
      measure() const = 0;

      /**
       * @name Finite strain (total Lagrangian)
       *
       * The questions a Newton solve at finite strain asks
       * (solve_finite_strain()); the linear questions above are its special
       * case at small strain. The vector and matrix types are the serial
       * ones today.
       * @{
       */

      /**
       * @brief Adds the internal force f_int(u) = int P : grad N dX of the
       * law @p material at the displacement @p u to @p force and, with
       * @p tangent (not nullptr, on sparsity_pattern()), its tangent
       * d f_int / du to it, on all cores. Returns the smallest det F at the
       * quadrature points (not positive: an element has inverted and the
       * force is not defined there).
       */
      virtual double
      internal_force(const Vector<double>                        &u,
                     const elasticity::HyperelasticMaterial<dim> &material,
                     Vector<double>                              &force,
                     SparseMatrix<double> *tangent) const = 0;

      /**
       * @brief Adds the follower pressures of the body at finite strain
       * (its 'pressure p' tractions, each scaled by its history's factor in
       * @p factors) at the displacement @p u to the residual @p residual
       * (f_int - f_ext: + p J F^-T N dA) and, with @p tangent (not nullptr,
       * on sparsity_pattern()), their load stiffness to it. Nothing at
       * small strain, where a pressure is a load case like any traction.
       */
      virtual void
      add_follower_pressure(const Vector<double>      &u,
                            const std::vector<double> &factors,
                            Vector<double>            &residual,
                            SparseMatrix<double>      *tangent) const = 0;

      /// The follower pressures at @p factors: each face's boundary id and
      /// its pressure (none at small strain).
      std::vector<std::pair<types::boundary_id, double>>
      follower_pressures(const std::vector<double> &factors) const;

      /**
       * @brief Every load on the body at the history factors @p factors and
       * the displacement @p u: external_load_vector(), and at finite strain
       * the follower pressures on the current surface.
       */
      Vector<double>
      applied_loads(const Vector<double>      &u,
                    const std::vector<double> &factors) const;

      /// The pattern of the stiffness and the tangent (all cell couplings).
      const SparsityPattern &
      sparsity_pattern() const;

      /// The supports, homogeneous: the unknowns every increment keeps.
      const AffineConstraints<double> &
      support_constraints() const;

      /**
       * @brief The Cauchy stress sigma = F S F^T / det F of the law
       * @p material at the reference point @p location.
       */
      SymmetricTensor<2, dim>
      cauchy_stress(
        const Vector<double>                        &u,
        const Point<dim>                            &location,
        const elasticity::HyperelasticMaterial<dim> &material) const;

      /**
       * @brief The supports' prescribed values at the load histories'
       * factors @p factors (each support scaled by its history's factor),
       * zero at the unknowns no support holds. At finite strain a face
       * motion turns its face by the exact rotation R(f r) of its rotation
       * vector r at its history's factor f (FaceMotion), which a linear
       * field in x interpolates exactly as the small rotation's does.
       */
      Vector<double>
      prescribed_values(const std::vector<double> &factors) const;
      /** @} */

      /**
       * @brief The exact geometry after degree elevation, Subdivisions and
       * Refinements, patch @p p of it: the NURBS analysis space, or the map
       * the Lagrange mesh's cells follow.
       */
      virtual const nurbs::NurbsPatch<dim> &
      geometry_patch(const unsigned int p = 0) const = 0;

      /// @brief Number of patches of the geometry (faces p * 2 dim + f).
      virtual unsigned int
      n_patches() const
      {
        return 1;
      }

      /// @brief The face @p face as scenes write it (discretization::
      /// face_name()).
      std::string
      face_name(const types::boundary_id face) const
      {
        return discretization::face_name(face, dim);
      }

    protected:
      /// move_surfaces() (@p u) and reset_surfaces() (nullptr) in the
      /// discretisation's surface geometry.
      virtual void
      move_surface_geometry(const Vector<double> *u) const = 0;

      /**
       * @brief Builds the discrete space: fills n_unknowns,
       * dof_locations, sparsity and the support constraints (homogeneous,
       * and the prescribed values at factor 1 in prescribed_constraints).
       */
      virtual void
      setup_space() = 0;

      /**
       * @brief Assembles the unconstrained stiffness into system_matrix and
       * the external loads (tractions, body force, point loads) at load
       * factor 1 into load_rhs, using all cores.
       */
      virtual void
      assemble() = 0;

      /// Discretisation settings.
      const DiscretizationSettings settings;

      /// Number of unknowns.
      types::global_dof_index n_unknowns = 0;
      /// Location of each scalar unknown's control point / node (for rigid
      /// modes): dof_locations[i] belongs to unknown i.
      std::vector<Point<dim>> dof_locations;
      /// Component of each unknown.
      std::vector<unsigned int> dof_components;
      /// Whether each unknown's basis function is non-zero somewhere on the
      /// body's boundary (filled by setup_space(); the pins of free rigid
      /// modes are chosen away from it, see find_free_rigid_modes()).
      std::vector<bool> on_boundary;
      /// Supports, homogeneous.
      AffineConstraints<double> constraints;
      /// Supports with the prescribed values at displacement factor 1.
      AffineConstraints<double> prescribed_constraints;
      /// Sparsity of the stiffness.
      SparsityPattern sparsity;
      /// The pattern of K's reaction rows (keep_reaction_rows_only();
      /// declared before K, which it must outlive).
      std::unique_ptr<SparsityPattern> reaction_sparsity;
      /// Whether K holds its reaction rows only.
      bool reduced_to_reaction_rows = false;
      /// Unconstrained stiffness (assembled by the derived class).
      SparseMatrix<double> system_matrix;
      /**
       * The cells assemble() adds, in the body's cell order (the order of
       * output_cells()): [first, end). All of them, except under MPI when
       * the ranks of the body's group divide the assembly (each its share;
       * MUMPS sums the shares of K, the group sums the load vectors).
       */
      std::pair<unsigned int, unsigned int> assembly_cells{
        0,
        std::numeric_limits<unsigned int>::max()};
      /// External loads of history 0 at factor 1 (history_rhs[0]).
      Vector<double> load_rhs;
      /// External loads of each load history at factor 1.
      std::vector<Vector<double>> history_rhs;
      /// The unknowns each support (BodyDescription::dirichlet) prescribes.
      std::vector<std::vector<types::global_dof_index>> dirichlet_dofs;
      /// Load history of each unknown with a prescribed value.
      std::map<types::global_dof_index, unsigned int> prescribed_history;

      /**
       * @brief Assembles K (with history 0) and one load vector per load
       * history: @p assemble(body_force, tractions, matrix, rhs) adds K and
       * the loads of the given tractions and body force, @p point_load adds
       * one point load to a load vector.
       */
      void
      assemble_history_loads(
        const std::function<void(const elasticity::BodyForce<dim> &,
                                 const std::vector<NeumannCondition<dim>> &,
                                 SparseMatrix<double> &,
                                 Vector<double> &)> &assemble,
        const std::function<void(const PointLoad<dim> &, Vector<double> &)>
          &point_load);

    private:
      /**
       * @brief Refuses (base::ExcInput) a load vector with an entry that is
       * not finite or past base::largest_squarable_entry(): the loads of the
       * scene are beyond double arithmetic, and every solve would overflow.
       */
      void
      check_load_magnitudes() const;

      /// The free rigid modes and their pins (solve_constraints).
      void
      find_free_rigid_modes();

      /// Per unknown, how strongly the choice of the rigid-mode pins prefers
      /// it: 1e-3 on the boundary, between 1 and 2 inside, growing with the
      /// depth (steps through K's pattern to the nearest boundary unknown)
      /// and, among equally deep ones, with nearness to the centroid; all 1
      /// when no unknown is interior.
      std::vector<double>
      pin_preference() const;

      /**
       * @brief The consistent loads @p c (one per rotation axis: z in 2D;
       * x, y, z in 3D) of the tractions t_a = e_a x (x - x_c) on @p face,
       * x_c its centroid, zero on constrained unknowns, and their moments
       * @p J (J_ab = int (|y|^2 delta_ab - y_a y_b), y = x - x_c): pure
       * moments, the linear tractions a distributing coupling spreads a
       * moment or a rotation constraint as.
       */
      void
      face_rotation_loads(const types::boundary_id     face,
                          std::vector<Vector<double>> &c,
                          FullMatrix<double>          &J) const;

      /**
       * @brief Holds the rotations BodyDescription::hold_rotation_face
       * names: the free rigid modes R_h that the constraints C_h^T u = 0
       * (the consistent loads of linear tractions t = e_a x (x - x_c) on
       * the face, pure moments) fix are removed from the free modes; every
       * solve becomes u = P K^+ P^T f with P = I - R_h S^-T C_h^T and
       * S = R_h^T C_h, K^+ the pinned solve. P^T adds the moment reaction
       * lambda C_h that balances the loads in the held modes; P adds the
       * held rigid motion that meets the constraints.
       */
      void
      hold_rotations();

      /**
       * @brief F <- (P^T C)^T K^+ (P^T C) from F = C^T K^+ C (the Schur
       * complement's flexibility of the point forces C given by
       * @p operators and @p directions): with A = R_h^T C, B = C^T K^+ C_h,
       * M = S^-1 A and Gamma = C_h^T K^+ C_h,
       * F - B M - M^T B^T + M^T Gamma M (RigidModes: R_h, C_h, S).
       */
      void
      correct_for_held_modes(const std::vector<PointOperator<dim>> &operators,
                             const std::vector<Tensor<1, dim>>     &directions,
                             FullMatrix<double>                    &F) const;


      void
      factorize_matrix(
        const std::vector<types::global_dof_index> &interface_dofs,
        const std::function<void()>                &matrix_read = {});

      /// Scene description (owned; body.h only forward-declares it).
      std::unique_ptr<const BodyDescription<dim>> body_description;
      /// Supports and the pins of free rigid modes: zero in every solve.
      AffineConstraints<double> solve_constraints;
      /// The factorisation (MUMPS, UMFPACK or CG with AMG); defined in
      /// body.cc so that this header stays free of solver libraries.
      struct LinearSolver;
      std::unique_ptr<LinearSolver> linear_solver;
      ParallelLayout                layout;
      /// set_progress_stream().
      std::ostream *progress_stream = nullptr;
      /// Whether K and the load vectors were assembled on this rank.
      bool assembled = false;
      /// The thread move_surfaces() moved the surfaces for (none: the
      /// reference configuration).
      mutable std::atomic<std::thread::id> surfaces_mover{};
      /// Whether every rank of the layout's world holds K whole
      /// (ParallelLayout::matrix_everywhere, or ensure_assembled(), which
      /// every rank calls): memory_record()'s K is then replicated.
      bool assembled_everywhere = false;
      /// Whether K holds this rank's share of the group's cells only (the
      /// load vectors are whole: summed over the group).
      bool assembled_share = false;
      /// Whether the ranks of the layout's group divide the assembly: a
      /// direct solver (MUMPS sums the shares) on a group of several ranks.
      bool
      shares_assembly() const;
      /// Assembles this rank's share of the group's cells and sums the load
      /// vectors over the group (collective on the group).
      void
      assemble_share();
      /// K u for the whole K: this rank's K, or the sum of the group's
      /// shares (collective on the group then).
      Vector<double>
      stiffness_times(const Vector<double> &u) const;
      /// n_matrix_entries(), from the root where K is not assembled.
      std::size_t matrix_entries = 0;

      /// solve() on this rank's share of the factorisation (collective on
      /// the layout's group; the root's vectors hold the solutions).
      void
      solve_in_group(std::vector<Vector<double>> &rhs_and_solutions) const;
      /// solve_in_group() without the held modes' projections: K^+ with the
      /// pins of every free rigid mode.
      void
      solve_pinned(std::vector<Vector<double>> &rhs_and_solutions) const;
      /// Solution of each load history at factor 1.
      std::vector<Vector<double>> u_history;
      /// The free and the held rigid modes, the pins' choice.
      RigidModes<dim> rigid_modes;
      /// The pinned responses K^+ C_h of the held modes' loads (for the
      /// Schur-complement flexibility).
      std::vector<Vector<double>> held_response;
    };

    /**
     * @brief Creates the body the settings ask for (NURBS or Lagrange).
     */
    template <int dim>
    std::unique_ptr<Body<dim>>
    create_body(const BodyDescription<dim>   &description,
                const DiscretizationSettings &settings);
  } // namespace discretization
} // namespace igabde

#endif
