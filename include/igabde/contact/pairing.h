#ifndef igabde_contact_pairing_h
#define igabde_contact_pairing_h

#include <igabde/base/choice_names.h>

#include <igabde/contact/contact_surface.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    using namespace dealii;

    /**
     * @brief One contact pair: a point on Body 1 and the point of the
     * surface it faces, with the local frame (rows: normal, tangents; the
     * normal is the facing surface's outward normal, pointing into Body 1),
     * the initial normal gap and the share of a uniform pressure the pair
     * carries. A weighted-gap pair is a basis function of Body 1's face:
     * x1, x2 and the gap are then its weighted means and op1, op2 the
     * weighted means of the point operators over its support.
     */
    template <int dim>
    struct ContactPair
    {
      Point<dim>     x1;
      Point<dim>     x2;
      Tensor<2, dim> frame;
      /// Body 1's outward unit normal at x1 (weighted-gap pairs: minus the
      /// frame's normal).
      Tensor<1, dim> normal1;
      double         gap  = 0.;
      double         area = 0.;
      /// Operators of the two points (op2 empty on an obstacle).
      discretization::PointOperator<dim> op1, op2;
      /// The indices of the slave body (op1) and of the master body (op2)
      /// in the contact stage's list of deformable bodies; master_body is
      /// numbers::invalid_unsigned_int against an obstacle, which
      /// obstacle then names (its index in the stage's obstacles).
      unsigned int slave_body = 0, master_body = 1;
      unsigned int obstacle = numbers::invalid_unsigned_int;
      /// The contact interaction the pair belongs to (0: the first), and
      /// its Coulomb friction coefficient.
      unsigned int interaction          = 0;
      double       friction_coefficient = 0.;
      /// What the pair is on the slave side, the same in every pairing of
      /// the interaction whatever the configuration (finite sliding matches
      /// pairs by it): the weighted gap's slave basis function (its first
      /// unknown); invalid where a pairing does not say.
      types::global_dof_index slave_key = numbers::invalid_dof_index;
      /// Finite sliding with friction (ContactStage::pairs_at()): the slave
      /// point's displacement over the load step relative to the master's
      /// material point it faced at the step's start (the step's pair's
      /// operators applied to the step's displacement); its components on
      /// the current tangents are the step's slip. Zero elsewhere.
      Tensor<1, dim> step_slip;

      /**
       * @brief The operator by which the pair reads body @p b's unknowns,
       * or nullptr when it does not touch @p b; @p sign is +1 on the slave
       * body and -1 on the master (the pair's relative displacement is the
       * slave point's less the master point's).
       */
      const discretization::PointOperator<dim> *
      operator_on(const unsigned int b, double &sign) const
      {
        sign = (b == slave_body ? 1. : -1.);
        return b == slave_body ? &op1 : b == master_body ? &op2 : nullptr;
      }
    };

    /**
     * @brief A pair's derivatives by the unknowns of its two bodies at the
     * configuration it was formed on (finite sliding's full tangent in
     * closed form): the gap's, the unit normal's components' and those of
     * each weight of op1 and op2, in their order. An unknown is (0, dof)
     * of the slave body or (1, dof) of the master body.
     */
    template <int dim>
    struct PairDerivatives
    {
      using Unknown  = std::pair<unsigned int, types::global_dof_index>;
      using Gradient = std::vector<std::pair<Unknown, double>>;
      Gradient                  gap;
      std::array<Gradient, dim> normal;
      std::vector<Gradient>     op1, op2;
    };

    /**
     * @brief The slave points a pairing left out at set-up, and why: a
     * point whose outward normal does not point against the master's at
     * its closest point (the part of a face that turns away, such as the
     * far side of a disc), and a point whose closest point is not its
     * orthogonal projection (the projection is clamped to the master's
     * edge: the point lies beyond the master's extent), and a point whose
     * projection did not settle. Points are
     * Body::surface_points() for point pairings, the quadrature points of
     * the slave face for the weighted gap.
     */
    template <int dim>
    struct PairingExclusions
    {
      /// Slave points considered.
      unsigned int candidates = 0;
      /// Left out: not facing the master.
      unsigned int not_facing = 0;
      /// Left out: beyond the master's extent.
      unsigned int outside = 0;
      /// Left out: the closest-point projection did not settle (a face
      /// folding back on itself far from the slave point).
      unsigned int unprojected = 0;
      /// Left out: the slave's or the master's normal there is degenerate
      /// (zero: a point of a collapsed edge, where the face's measure
      /// vanishes).
      unsigned int degenerate = 0;
      /// Left out: farther from its closest master point than the search
      /// distance (0: no such limit).
      unsigned int beyond          = 0;
      double       search_distance = 0.;
      /// The first point of each kind (valid when its count is positive).
      Point<dim> first_not_facing, first_outside, first_unprojected,
        first_degenerate, first_beyond;
      /// Whether the points are quadrature points (weighted gap).
      bool quadrature_points = false;

      /// Whether the slave point at @p s with outward normal @p n_s is
      /// paired with the master point at @p m, normal @p n_m; counts it
      /// otherwise. @p size is the scale of round-off (the slave face's
      /// size).
      bool
      keep(const Point<dim>     &s,
           const Tensor<1, dim> &n_s,
           const Point<dim>     &m,
           const Tensor<1, dim> &n_m,
           const double          size);

      /// Counts the slave point at @p s, whose projection did not settle.
      void
      leave_out_unprojected(const Point<dim> &s);

      /// All points left out.
      unsigned int
      n_left_out() const
      {
        return not_facing + outside + unprojected + degenerate + beyond;
      }
    };

    /**
     * @brief Thrown by a point pairing when a slave point it keeps has a
     * non-positive tributary area (a repeated control point on the slave
     * face); the message says where. The contact stage pairs that
     * interaction by the weighted gap instead.
     */
    class ExcNonPositiveTributaryArea : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    /**
     * @brief How Body 1's contact face is paired with the surface it faces.
     * Implementations: NodeToNodePairing ("node-to-node", matching
     * surfaces), NodeToSurfacePairing ("node-to-surface", closest point),
     * both PointPairing, and WeightedGapPairing ("weighted-gap" and
     * "weighted-gap-standard", one pair per basis function of the slave
     * face, mortar-like). A new strategy is
     * one class deriving from this one (or from PointPairing) plus one line
     * in create_pairing_strategy().
     */
    template <int dim>
    class PairingStrategy
    {
    public:
      virtual ~PairingStrategy() = default;

      /**
       * @brief The pairs of the patch faces @p slave_faces of @p slave_body
       * (Body 1: one face, or several of a multi-patch body forming one
       * surface) against @p master, frames from the master normal. Slave
       * points that do not face the master or lie beyond it are left out
       * and counted (exclusions()). Throws an input error, naming
       * @p context, when no slave point faces the master or Body 1
       * initially penetrates.
       */
      virtual std::vector<ContactPair<dim>>
      make_pairs(const discretization::Body<dim>       &slave_body,
                 const std::vector<types::boundary_id> &slave_faces,
                 const ContactSurface<dim>             &master,
                 const std::string                     &context) const = 0;

      /**
       * @brief The pairs of make_pairs() whose slave_key is in @p keys
       * (sorted), each as make_pairs() forms it, in its order; for finite
       * sliding's derivatives, which form a few pairs again at many
       * configurations. Neither refuses a configuration in which nothing
       * faces the master nor fills exclusions(). This one forms every pair
       * and keeps those asked for; WeightedGapPairing integrates only the
       * slave elements that the asked functions live on.
       */
      virtual std::vector<ContactPair<dim>>
      make_pairs_of(const discretization::Body<dim>            &slave_body,
                    const std::vector<types::boundary_id>      &slave_faces,
                    const ContactSurface<dim>                  &master,
                    const std::string                          &context,
                    const std::vector<types::global_dof_index> &keys) const;

      /**
       * @brief make_pairs_of() with each pair's derivatives by the bodies'
       * unknowns (PairDerivatives, one per pair, in @p derivatives), where
       * the pairing has them in closed form against @p master; false, and
       * nothing formed, where it does not (this one: never), and the full
       * tangent then takes differences of make_pairs_of().
       */
      virtual bool
      make_pairs_with_derivatives(
        const discretization::Body<dim>            &slave_body,
        const std::vector<types::boundary_id>      &slave_faces,
        const ContactSurface<dim>                  &master,
        const std::string                          &context,
        const std::vector<types::global_dof_index> &keys,
        std::vector<ContactPair<dim>>              &pairs,
        std::vector<PairDerivatives<dim>>          &derivatives) const;

      /// What the last make_pairs() left out (PairingExclusions); when it
      /// would leave out every point it throws the input error instead.
      const PairingExclusions<dim> &
      exclusions() const
      {
        return left_out;
      }

      /// Slave points farther than @p distance from their closest master
      /// point are left out (0, the default: no limit).
      void
      set_search_distance(const double distance)
      {
        search_distance = distance;
      }

    protected:
      /// Filled by make_pairs().
      mutable PairingExclusions<dim> left_out;
      double                         search_distance = 0.;
    };



    /**
     * @brief Pairs of points: Body 1's candidate points
     * (Body::surface_points()) each with the point of the master surface it
     * faces, chosen by facing_point().
     */
    template <int dim>
    class PointPairing : public PairingStrategy<dim>
    {
    public:
      /// make_pairs() below on the points of Body::surface_points() of
      /// every face; a point that two faces share (on the edge where two
      /// patches meet) is one point, carrying both tributary areas.
      std::vector<ContactPair<dim>>
      make_pairs(const discretization::Body<dim>       &slave_body,
                 const std::vector<types::boundary_id> &slave_faces,
                 const ContactSurface<dim>             &master,
                 const std::string                     &context) const override;

      /**
       * @brief The pairs of the points @p slave (Body 1's contact face)
       * against @p master: on an obstacle the projection, on a deformable
       * surface the point facing_point() chooses; frames from the master
       * normal.
       */
      std::vector<ContactPair<dim>>
      make_pairs(const std::vector<discretization::SurfacePoint<dim>> &slave,
                 const ContactSurface<dim>                            &master,
                 const std::string &context) const;

    protected:
      /**
       * @brief The point of the deformable surface @p master facing the
       * slave point @p s; @p nearest is the master sample nearest to it and
       * @p size the size of the slave face (the scale of tolerances).
       */
      virtual discretization::SurfacePoint<dim>
      facing_point(const discretization::SurfacePoint<dim> &s,
                   const discretization::SurfacePoint<dim> &nearest,
                   const ContactSurface<dim>               &master,
                   const double                             size,
                   const std::string                       &context) const = 0;
    };

    /**
     * @brief Node-to-node: every point of Body 1 has a coincident point on
     * a deformable master face (matching meshes; an error otherwise).
     */
    template <int dim>
    class NodeToNodePairing : public PointPairing<dim>
    {
    protected:
      discretization::SurfacePoint<dim>
      facing_point(const discretization::SurfacePoint<dim> &s,
                   const discretization::SurfacePoint<dim> &nearest,
                   const ContactSurface<dim>               &master,
                   const double                             size,
                   const std::string &context) const override;
    };

    /**
     * @brief Node-to-surface: the coincident master point where the
     * surfaces match, else the closest point of the master surface (exact
     * on NURBS faces).
     */
    template <int dim>
    class NodeToSurfacePairing : public PointPairing<dim>
    {
    protected:
      discretization::SurfacePoint<dim>
      facing_point(const discretization::SurfacePoint<dim> &s,
                   const discretization::SurfacePoint<dim> &nearest,
                   const ContactSurface<dim>               &master,
                   const double                             size,
                   const std::string &context) const override;
    };

    /**
     * @brief Weighted gap (mortar-like): the contact pressure lives in the
     * trace space of Body 1's contact face, one pair per basis function
     * N_j of the face (NURBS basis of the face, or the FE_Q face basis).
     *
     * Integrals run over the slave face, the master side found by closest
     * point projection of each quadrature point: tributary area
     * A_j = int N_j dGamma; operators op1_j = int N_j R_A dGamma / A_j (a
     * row of the face's mass matrix) and op2_j = int N_j R_B(pi(x)) dGamma
     * / A_j, so that the pair's relative displacement is the N_j-weighted
     * mean of u1 - u2(pi(x)) and its force p_j distributes as the pressure
     * p_j / A_j N_j on both faces; gap g_j = int N_j g dGamma / A_j with g
     * the pointwise normal gap; frame from the N_j-weighted mean of the
     * master normals. Each slave element is cut where the projection
     * crosses a master element edge (located along the element's centre
     * lines, in every face direction), and every piece is integrated with
     * Gauss rules exact for the product of the two polynomial bases: on
     * flat faces with edges of the master grid along the slave's
     * parametric lines (boxes, the V3 patch test) the integrals are exact
     * and a uniform pressure is transmitted exactly; elsewhere the cuts
     * are those of the centre lines.
     */
    template <int dim>
    class WeightedGapPairing : public PairingStrategy<dim>
    {
    public:
      /**
       * @brief With @p dual (the default, "weighted-gap"), gaps, slips and
       * operators are weighted by the dual basis psi_j of the slave face
       * instead of N_j: on each slave element e, psi_j = sum_k A_jk N_k with
       * A = D M^{-1}, M_jk = int_e N_j N_k, D = diag(int_e N_j), so that
       * int psi_j N_k = delta_jk int N_j (biorthogonal). The pair's force
       * then goes to the slave control point (node) j alone and its
       * pressure p_j = force / int N_j is the N_j-weighted mean of the
       * contact pressure, which does not oscillate at the edge of a contact
       * zone the way the coefficients of the N_j expansion do
       * ("weighted-gap-standard", @p dual false). Both sum to one, so a
       * uniform pressure is transmitted exactly either way. Areas, frames
       * and locations are N_j-weighted in both.
       */
      explicit WeightedGapPairing(const bool dual = true);

      std::vector<ContactPair<dim>>
      make_pairs(const discretization::Body<dim>       &slave_body,
                 const std::vector<types::boundary_id> &slave_faces,
                 const ContactSurface<dim>             &master,
                 const std::string                     &context) const override;

      /// Integrates the slave elements on which one of the basis
      /// functions @p keys lives, and forms their pairs from those
      /// integrals (the same numbers as make_pairs(): a function's
      /// integrals are the sums over its elements, in the same order).
      /// Where some basis function of the slave faces is held by supports
      /// (merged into its neighbour by make_pairs()), it forms every pair.
      std::vector<ContactPair<dim>>
      make_pairs_of(
        const discretization::Body<dim>            &slave_body,
        const std::vector<types::boundary_id>      &slave_faces,
        const ContactSurface<dim>                  &master,
        const std::string                          &context,
        const std::vector<types::global_dof_index> &keys) const override;

      /**
       * With the derivatives in closed form where the master's normal is
       * continuous (ContactSurface::normal_continuous()): the integrands
       * are then continuous across the element cuts, which therefore
       * move without changing the integrals to first order, and the
       * derivatives are those of the integrands at the quadrature points
       * (internal::add_element_derivatives()). Where the normal turns a
       * little at a cut (a repeated knot or two faces meeting
       * tangentially, bent by the strain), the cut's motion times that
       * turn is left out. Against a faceted master the normal jumps at
       * the cuts and the full tangent takes differences.
       */
      bool
      make_pairs_with_derivatives(
        const discretization::Body<dim>            &slave_body,
        const std::vector<types::boundary_id>      &slave_faces,
        const ContactSurface<dim>                  &master,
        const std::string                          &context,
        const std::vector<types::global_dof_index> &keys,
        std::vector<ContactPair<dim>>              &pairs,
        std::vector<PairDerivatives<dim>>          &derivatives) const override;

    private:
      /// make_pairs() and make_pairs_of(): all pairs when @p keys is
      /// nullptr; with their derivatives where @p derivatives is not.
      std::vector<ContactPair<dim>>
      form_pairs(
        const discretization::Body<dim>            &slave_body,
        const std::vector<types::boundary_id>      &slave_faces,
        const ContactSurface<dim>                  &master,
        const std::string                          &context,
        const std::vector<types::global_dof_index> *keys,
        std::vector<PairDerivatives<dim>> *derivatives = nullptr) const;

      /// Weights psi_j (dual basis) instead of N_j.
      const bool dual;
    };

    /** @brief Contact/Pairing. */
    enum class Pairing
    {
      /// Point pairs: the coincident or closest point of the master face.
      node_to_surface,
      /// Point pairs on matching meshes only.
      node_to_node,
      /// One pair per basis function of the slave face, dual weights.
      weighted_gap,
      /// One pair per basis function, the basis functions as weights.
      weighted_gap_standard
    };

    /** @brief The names of Pairing as the scene writes them (one row per
     * strategy create_pairing_strategy() knows). */
    inline constexpr base::ChoiceNames<Pairing, 4> pairing_names = {
      {{Pairing::node_to_surface, "node-to-surface"},
       {Pairing::node_to_node, "node-to-node"},
       {Pairing::weighted_gap, "weighted-gap"},
       {Pairing::weighted_gap_standard, "weighted-gap-standard"}}};

    /** @brief The name of @p pairing as the scene writes it. */
    inline std::string
    to_string(const Pairing pairing)
    {
      return base::name_of(pairing_names, pairing);
    }

    /** @brief The strategy of @p pairing. */
    template <int dim>
    std::unique_ptr<PairingStrategy<dim>>
    create_pairing_strategy(const Pairing pairing);


    /**
     * @brief Rows n, t1[, t2]: an orthonormal frame with the unit normal
     * @p n first (in 3D the first tangent is the coordinate axis least
     * aligned with n, made orthogonal to it).
     */
    template <int dim>
    Tensor<2, dim>
    local_frame(const Tensor<1, dim> &n);

    /**
     * @brief The frame with the unit normal @p n whose tangents follow
     * those of @p near (a frame at a nearby normal): in 3D near's first
     * tangent made orthogonal to n (local_frame(n) if it is about parallel
     * to n); in 2D local_frame(n). Finite sliding keeps a pair's tangents
     * continuous so, where local_frame() would switch its axis.
     */
    template <int dim>
    Tensor<2, dim>
    local_frame(const Tensor<1, dim> &n, const Tensor<2, dim> &near);

    /**
     * @brief The change of local_frame(@p n, @p near) for a change @p dn
     * of the unit normal (orthogonal to it): its derivative in the
     * direction @p dn, with the axis that local_frame() picks held.
     */
    template <int dim>
    Tensor<2, dim>
    local_frame_change(const Tensor<1, dim> &n,
                       const Tensor<2, dim> &near,
                       const Tensor<1, dim> &dn);

    namespace internal
    {
      /// The refusal, naming @p context, when the two contact faces do not
      /// face each other at @p location.
      template <int dim>
      std::string
      not_facing(const std::string         &context,
                 const Point<dim>          &location,
                 const ContactSurface<dim> &master);

      /// The refusal when every slave point was left out (@p exclusions):
      /// none faces @p master, or none lies within its extent.
      template <int dim>
      std::string
      nothing_faces(const std::string            &context,
                    const PairingExclusions<dim> &exclusions,
                    const ContactSurface<dim>    &master);

      /// The refusal of an initial penetration by @p gap (negative).
      template <int dim>
      std::string
      penetrates(const std::string         &context,
                 const ContactSurface<dim> &master,
                 const double               gap);
    } // namespace internal
  }   // namespace contact
} // namespace igabde

#endif
