#ifndef igabde_contact_pairing_h
#define igabde_contact_pairing_h

#include <igabde/contact/contact_surface.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
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
     * carries.
     */
    template <int dim>
    struct ContactPair
    {
      Point<dim>     x1;
      Point<dim>     x2;
      Tensor<2, dim> frame;
      double         gap  = 0.;
      double         area = 0.;
      /// Operators of the two points (op2 empty on an obstacle).
      discretization::PointOperator<dim> op1, op2;
    };

    /**
     * @brief How Body 1's contact points are paired with the surface they
     * face. Implementations: NodeToNodePairing ("node-to-node", matching
     * surfaces), NodeToSurfacePairing ("node-to-surface", closest point).
     * A new strategy is one class deriving from this one (it chooses the
     * facing point of a slave point on a deformable surface) plus one line
     * in create_pairing_strategy().
     */
    template <int dim>
    class PairingStrategy
    {
    public:
      virtual ~PairingStrategy() = default;

      /// The name the factory knows the strategy by.
      virtual std::string
      name() const = 0;

      /**
       * @brief The pairs of the points @p slave (Body 1's contact face)
       * against @p master: on an obstacle the projection, on a deformable
       * surface the point facing_point() chooses; frames from the master
       * normal. Throws an input error, naming @p context, when the surfaces
       * do not face each other or Body 1 initially penetrates.
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
    class NodeToNodePairing : public PairingStrategy<dim>
    {
    public:
      std::string
      name() const override;

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
    class NodeToSurfacePairing : public PairingStrategy<dim>
    {
    public:
      std::string
      name() const override;

    protected:
      discretization::SurfacePoint<dim>
      facing_point(const discretization::SurfacePoint<dim> &s,
                   const discretization::SurfacePoint<dim> &nearest,
                   const ContactSurface<dim>               &master,
                   const double                             size,
                   const std::string &context) const override;
    };

    /**
     * @brief The strategy @p name names ("node-to-node",
     * "node-to-surface"); an input error listing them otherwise.
     */
    template <int dim>
    std::unique_ptr<PairingStrategy<dim>>
    create_pairing_strategy(const std::string &name);

    /// The names create_pairing_strategy() knows.
    std::vector<std::string>
    available_pairing_strategies();

    /**
     * @brief Rows n, t1[, t2]: an orthonormal frame with the unit normal
     * @p n first (in 3D the first tangent is the coordinate axis least
     * aligned with n, made orthogonal to it).
     */
    template <int dim>
    Tensor<2, dim>
    local_frame(const Tensor<1, dim> &n);
  } // namespace contact
} // namespace igabde

#endif
