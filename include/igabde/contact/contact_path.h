#ifndef igabde_contact_contact_path_h
#define igabde_contact_contact_path_h

#include <igabde/discretization/body.h>
#include <igabde/discretization/factorization_request.h>

#include <igabde/contact/condensation.h>
#include <igabde/contact/contact_operator.h>
#include <igabde/contact/coupled_operator.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/sliding.h>

#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    using namespace dealii;

    /**
     * @brief Builds the coupled system of the full path from the bodies, the
     * pairs (whose body indices say which bodies each one couples), the
     * components per pair and the rigid-mode columns G. The concrete system
     * lives outside the contact layer (coupled/coupled_system.h,
     * coupled::coupled_factory()).
     */
    template <int dim>
    struct FiniteSliding;

    template <int dim>
    using CoupledFactory = std::function<std::unique_ptr<CoupledOperator>(
      const std::vector<const discretization::Body<dim> *> &,
      const std::vector<ContactPair<dim>> &,
      const unsigned int,
      const Eigen::MatrixXd &,
      const FiniteSliding<dim> &)>;

    /**
     * @brief Finite sliding on the full path (Contact/Sliding = finite): how
     * the coupled system forms its pairs again at every iterate
     * (ContactOperator::update_geometry()).
     */
    /**
     * @brief A pair on the configuration of FiniteSliding::linearization_of
     * with the derivatives of what the Newton matrix differentiates by the
     * unknowns (body, dof) of the deformable bodies: the gap, each entry of
     * the frame (rows: normal, tangents), the step's slip
     * (ContactPair::step_slip) and each weight of op1 and op2.
     */
    template <int dim>
    struct PairLinearization
    {
      using Unknown  = std::pair<unsigned int, types::global_dof_index>;
      using Gradient = std::vector<std::pair<Unknown, double>>;
      ContactPair<dim>                           pair;
      Gradient                                   gap;
      std::array<std::array<Gradient, dim>, dim> frame;
      std::array<Gradient, dim>                  slip;
      std::vector<Gradient>                      op1, op2;
    };

    template <int dim>
    struct FiniteSliding
    {
      /// The pairs, in the contact path's order, on the configuration that
      /// the displacement correction w (every body's unknowns, in the
      /// system's order) reaches: operators, frames and gaps there. Empty:
      /// small sliding, the pairs of prepare() throughout.
      std::function<std::vector<ContactPair<dim>>(const Eigen::VectorXd &)>
        pairs_at;
      /// The pairs of pairs_at() with the given indices, in that order, as
      /// pairs_at() forms them, at less cost than all of them (the full
      /// tangent's differences form the pairs in contact again at every
      /// group of unknowns). Empty: pairs_at() and a pick.
      std::function<
        std::vector<ContactPair<dim>>(const Eigen::VectorXd &,
                                      const std::vector<unsigned int> &)>
        pairs_of;
      /// The pairs of pairs_of() with their derivatives in closed form
      /// (PairLinearization, in that order), or false where a pairing has
      /// none for its master (PairingStrategy::
      /// make_pairs_with_derivatives()): the full tangent then takes
      /// differences of pairs_of(). Empty: differences.
      std::function<bool(const Eigen::VectorXd &,
                         const std::vector<unsigned int> &,
                         std::vector<PairLinearization<dim>> &)>
        linearization_of;
      /// The law's q of the solve, whose normal rows the gaps of pairs_at()
      /// replace (through ContactOperator::displacement_offset()).
      const Eigen::VectorXd *q = nullptr;
      /// Whether the Newton matrix takes the pairs' derivatives by the
      /// configuration (Contact/Sliding tangent = full), the pairs'
      /// operators at the iterate (frozen), or the first once the Newton
      /// iteration asks for it (auto; ContactOperator::
      /// want_exact_tangent()).
      SlidingTangent tangent = SlidingTangent::frozen;
    };

    /**
     * @brief A contact path between the bodies and the contact solver:
     * what each body must factorise for, how the contact problem is formed
     * once the bodies are factorised (the ContactOperator and the law's
     * data), and how the contact forces become displacement fields.
     * CondensedPath condenses onto the pairs (dense W from the Schur
     * complements), CoupledPath keeps the coupled system.
     */
    template <int dim>
    class ContactPath
    {
    public:
      virtual ~ContactPath() = default;

      /**
       * @brief What body @p b's factorisation must provide for this path
       * (a Schur interface on the pairs' unknowns, or none) and what must
       * stay after its load cases (K whole, the factor).
       */
      virtual discretization::FactorizationRequest<dim>
      factorization_request(
        const unsigned int                   b,
        const std::vector<ContactPair<dim>> &pairs) const = 0;

      /**
       * @brief Forms the contact problem from the factorised bodies:
       * leaves out the pairs that carry no information, fills @p contact
       * (the pairs kept, the rigid-mode columns and loads, the law's data,
       * and on the condensed path W) and builds the operator.
       */
      virtual void
      prepare(const std::vector<ContactPair<dim>> &pairs,
              CondensedContact<dim>               &contact) = 0;

      /** @brief The operator built by prepare(). */
      virtual ContactOperator &
      op() = 0;

      /**
       * @brief Adds the bodies' response to the contact forces to @p u:
       * @p loads are the forces as load vectors of each body, @p x the
       * solve's unknowns (w on the full path).
       */
      virtual void
      add_response(const std::vector<Vector<double>> &loads,
                   const ContactIterate              &x,
                   std::vector<Vector<double>>       &u) const = 0;

      /** @brief One line for the log on what prepare() formed. */
      virtual std::string
      description(const CondensedContact<dim> &contact) const = 0;

      /**
       * @brief The bodies' displacement @p u the next solve's corrections
       * start from and the load histories' factors @p factors, for the
       * bodies at finite strain (CoupledOperator::set_reference()); nothing
       * on the condensed path, which solves at small strain only.
       */
      virtual void
      set_reference(const std::vector<Vector<double>> &u,
                    const std::vector<double>         &factors)
      {
        (void)u;
        (void)factors;
      }

      /** @brief Nonzeros of a sparse Newton matrix (0 if none). */
      virtual double
      n_nonzeros() const
      {
        return 0.;
      }

      /**
       * @brief Finite sliding: the operator of the next prepare() forms its
       * pairs at every iterate by @p sliding's pairs_at() and pairs_of(),
       * and with its full_tangent differentiates them in its Newton matrix
       * (FiniteSliding; the path sets its q). The full path only.
       */
      virtual void
      set_finite_sliding(const FiniteSliding<dim> &sliding)
      {
        (void)sliding;
        AssertThrow(false,
                    ExcMessage("finite sliding is modelled on the full path "
                               "(Contact/Path = full)"));
      }
    };



    /** @brief The condensed path (condense(), CondensedOperator). */
    template <int dim>
    class CondensedPath : public ContactPath<dim>
    {
    public:
      /**
       * @param schur Whether the bodies factorise with a Schur interface
       * on the pairs' unknowns (Contact/Condensation = schur with the
       * direct solver); else one solve per pair direction.
       */
      CondensedPath(
        const std::vector<const discretization::Body<dim> *> &bodies,
        const unsigned int                                    n_components,
        const bool                                            schur,
        const std::string                                    &context,
        std::ostream                                         &log,
        const bool                                            progress);

      discretization::FactorizationRequest<dim>
      factorization_request(
        const unsigned int                   b,
        const std::vector<ContactPair<dim>> &pairs) const override;

      void
      prepare(const std::vector<ContactPair<dim>> &pairs,
              CondensedContact<dim>               &contact) override;

      ContactOperator &
      op() override;

      void
      add_response(const std::vector<Vector<double>> &loads,
                   const ContactIterate              &x,
                   std::vector<Vector<double>>       &u) const override;

      std::string
      description(const CondensedContact<dim> &contact) const override;

      /** @brief True: the condensation and the field recovery solve. */
    private:
      const std::vector<const discretization::Body<dim> *> bodies;
      const unsigned int                                   m;
      const bool                                           schur;
      const std::string                                    context;
      std::ostream                                        &log;
      const bool                                           progress;
      std::unique_ptr<CondensedOperator>                   condensed;
    };



    /** @brief The full path (the coupled system of a CoupledFactory). */
    template <int dim>
    class CoupledPath : public ContactPath<dim>
    {
    public:
      CoupledPath(const std::vector<const discretization::Body<dim> *> &bodies,
                  const unsigned int         n_components,
                  const CoupledFactory<dim> &factory,
                  const std::string         &context,
                  std::ostream              &log);

      discretization::FactorizationRequest<dim>
      factorization_request(
        const unsigned int                   b,
        const std::vector<ContactPair<dim>> &pairs) const override;

      void
      prepare(const std::vector<ContactPair<dim>> &pairs,
              CondensedContact<dim>               &contact) override;

      ContactOperator &
      op() override;

      void
      add_response(const std::vector<Vector<double>> &loads,
                   const ContactIterate              &x,
                   std::vector<Vector<double>>       &u) const override;

      std::string
      description(const CondensedContact<dim> &contact) const override;

      void
      set_reference(const std::vector<Vector<double>> &u,
                    const std::vector<double>         &factors) override;

      /** @brief Nonzeros of the coupled Newton matrix. */
      double
      n_nonzeros() const override;

      void
      set_finite_sliding(const FiniteSliding<dim> &sliding) override;

    private:
      const std::vector<const discretization::Body<dim> *> bodies;
      const unsigned int                                   m;
      const CoupledFactory<dim>                            factory;
      const std::string                                    context;
      std::ostream                                        &log;
      std::unique_ptr<CoupledOperator>                     coupled;
      /// set_finite_sliding() (pairs_at empty: small sliding).
      FiniteSliding<dim> sliding;
    };
  } // namespace contact
} // namespace igabde

#endif
