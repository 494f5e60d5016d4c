#ifndef igabde_contact_contact_law_h
#define igabde_contact_contact_law_h

#include <igabde/contact/contact_problem.h>

#include <Eigen/Dense>

#include <string>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief State of one contact pair at the end of a solve (or iteration).
     *
     * A closed pair without friction (mu = 0, or a frictionless scene with
     * no tangential unknowns) is "closed": it neither sticks nor slips. A
     * closed pair with friction whose friction radius is zero (a grazing
     * pair, p_n = 0) moves freely in the tangential directions and is
     * reported as slip. The numbers are the values of the `status` field
     * of the contact VTU (0 open, 1 stick, 2 slip, 3 closed).
     */
    enum class ContactStatus
    {
      open,
      stick,
      slip,
      closed
    };

    /** @brief "open", "stick", "slip" or "closed". */
    std::string
    to_string(const ContactStatus status);

    /**
     * @brief Radius of the friction disc in the B-differentiable equations.
     *
     * Both give the same solution set; Newton behaves differently.
     */
    enum class FrictionRadius
    {
      /** R = mu max(p_n, 0): the seed's H (Christensen-Pang, Siconos JM). */
      christensen_pang,
      /** R = mu max(p_n - r_n u_n, 0): Alart-Curnier (Siconos NSN_AC). */
      alart_curnier
    };

    /**
     * @brief The per-pair weights r_n, r_t of the B-differentiable
     * equations: r_n = c / W_nn and r_t = c / lambda_max(W_tt) per contact
     * (W_tt the tangential diagonal block, @p n_components rows per
     * contact), c = @p factor. A non-positive
     * diagonal entry falls back to c / max_i W_ii (and to c if W = 0).
     * On the full path (no W, a CoupledOperator) r_n = r_t = c k_i with
     * k_i the operator's pair stiffness.
     */
    struct PairWeights
    {
      Eigen::VectorXd r_n, r_t;
    };

    PairWeights
    pair_weights(const Eigen::MatrixXd &W,
                 const unsigned int     n_components,
                 const double           factor,
                 const double           shift = 0.);

    /**
     * @brief The piece of the contact law one pair is on, and the element of
     * the B-subdifferential of its residual there: dH = A du + B dp (d x d
     * blocks in the pair's local frame, normal first).
     */
    struct PairPiece
    {
      ContactStatus status = ContactStatus::open;
      /// Whether the normal equation is on its closed branch.
      bool            closed = false;
      Eigen::Matrix3d A      = Eigen::Matrix3d::Zero();
      Eigen::Matrix3d B      = Eigen::Matrix3d::Zero();
    };

    /**
     * @brief The contact law of one pair: the B-differentiable residual H
     * of the seed (method.md's H_n, H_t) and, if @p piece is not null, its
     * piece and B-derivative. This is the one place where the open, stick
     * and slip pieces and their tie rules are decided; every solver uses
     * it.
     *
     * With @p d components, forces @p p and relative displacements @p u of
     * the pair (local frame, gap included in u_n):
     * @code
     *   H_n = min(r_n u_n, p_n)
     *   H_t = p_t - Proj_{D(R)}(z),  z = p_t - r_t u_t,
     *   R   = mu max(p_n, 0)            (FrictionRadius::christensen_pang)
     *     or mu max(p_n - r_n u_n, 0)   (FrictionRadius::alart_curnier)
     * @endcode
     * Tie rules (the B-derivative element chosen on a kink):
     *  - min, r_n u_n < p_n: closed, A_nn = r_n;
     *  - min, r_n u_n >= p_n (the tie included): open, B_nn = 1;
     *  - |z| <= R, including z = 0 with R = 0: stick, A_tt = r_t I (so the
     *    slip tie |z| = R > 0 is stick);
     *  - |z| > R = 0: H_t = p_t, B_tt = I (the kink of R at p_n = 0 is
     *    dropped);
     *  - |z| > R > 0: slip, zhat = z/|z|, Gamma = (R/|z|)(I - zhat zhat^T):
     *    B_tt = I - Gamma, A_tt = r_t Gamma, B_tn = -mu zhat, and for
     *    Alart-Curnier also A_tn = mu r_n zhat.
     */
    void
    pair_law(const unsigned int   d,
             const double         mu,
             const double         r_n,
             const double         r_t,
             const FrictionRadius radius,
             const double        *p,
             const double        *u,
             double              *H,
             PairPiece           *piece);

    /**
     * @brief The penalty contact law of one pair (node-to-node penalty as
     * ANSYS applies it, and the inner law of the augmented Lagrangian):
     * the forces @p p as a function of the relative displacement @p u
     * (total normal gap u_n, tangential increments u_t of the step), with
     * the base forces @p lambda (normal multiplier, 0 for pure penalty;
     * tangential force at the start of the step, or the tangential
     * multiplier):
     * @code
     *   p_n  = max(0, lambda_n - k_n u_n)
     *   p_t* = lambda_t - k_t u_t                     (elastic trial)
     *   p_t  = p_t*                  if |p_t*| <= mu p_n   (stick)
     *        = mu p_n p_t* / |p_t*|  otherwise             (slip)
     * @endcode
     * (the Coulomb return mapping). The returned piece holds the
     * linearisation of H = p - P(u) = 0 in the PairPiece convention
     * dH = A du + B dp: B = I and A = -dP/du, the consistent tangent:
     * open A = 0; stick A_nn = k_n, A_tt = k_t I; slip A_nn = k_n,
     * A_tn = mu k_n t, A_tt = k_t (mu p_n / |p_t*|) (I - t t^T) with
     * t = p_t* / |p_t*|. An open pair (lambda_n - k_n u_n < 0) carries
     * no force in any direction; the tie (= 0) is closed with zero force,
     * so that pairs touching at the start enter the first Newton matrix
     * (otherwise the rigid-mode columns of a floating body vanish).
     *
     * @param d Components (1 frictionless, 2 or 3).
     * @param mu Friction coefficient (ignored if d = 1).
     * @param k_n Normal penalty stiffness (force per length), > 0.
     * @param k_t Tangential (stick) penalty stiffness, > 0 if d > 1.
     * @param lambda Base forces, d entries.
     * @param u Relative displacement, d entries.
     * @param p On return the forces, d entries.
     */
    PairPiece
    penalty_law(const unsigned int d,
                const double       mu,
                const double       k_n,
                const double       k_t,
                const double      *lambda,
                const double      *u,
                double            *p);

    /**
     * @brief Projection of x = (x_n, x_t) (@p d components) onto the
     * Coulomb cone |x_t| <= mu x_n, in place.
     */
    void
    project_on_cone(double *x, const unsigned int d, const double mu);

    /**
     * @brief Absolute natural-map (De Saxce/FCLIB) error
     * |p - P_K(p - u_hat)| with u_hat = u + mu |u_t| e_n per contact and K
     * the Coulomb cone {|p_t| <= mu p_n}; for frictionless problems
     * |p - max(0, p - u)|. This is Siconos' fc3d_compute_error before its
     * division.
     */
    double
    natural_map_error(const ContactData     &problem,
                      const Eigen::VectorXd &p,
                      const Eigen::VectorXd &u);

    /**
     * @brief natural_map_error() divided by |q|, as in the FCLIB paper.
     *
     * When |q| is about zero (|q| <= 1e-12 |u - q|, or |q| = 0) the
     * division is by the force scale |p| instead (1 if p = 0 too).
     */
    double
    relative_natural_map_error(const ContactData     &problem,
                               const Eigen::VectorXd &p,
                               const Eigen::VectorXd &u);

    /**
     * @brief Equilibrium error of the floating bodies |G^T p - b| (stored in
     * @p absolute), divided by the larger of |b| and ||G|^T |p||; 0 without
     * floating bodies.
     */
    double
    relative_equilibrium_error(const ContactData     &problem,
                               const Eigen::VectorXd &p,
                               double                &absolute);

    /**
     * @brief Scale-invariant ("balanced") natural-map error:
     * |p - P_K(p - rho_c u_hat)| / |rho q| with rho_c = 1/W_nn of each
     * contact (a stiffness), so that forces are compared with forces. It
     * vanishes exactly where natural_map_error() does, and is unchanged when
     * forces and displacements are rescaled independently (the FCLIB error
     * is not: with W, q scaled by 1e6 it weights force errors by 1e-6).
     * Falls back to division by |p| when |q| is about zero. The stiffness
     * scale rho_c is given (@p unit_weights .r_n, the weights at factor 1
     * of the operator that relates u to p: 1/W_nn on the condensed path,
     * the pair stiffness of the underlying elements on the full path).
     */
    double
    balanced_natural_map_error(const ContactData     &problem,
                               const PairWeights     &unit_weights,
                               const Eigen::VectorXd &p,
                               const Eigen::VectorXd &u);
  } // namespace contact
} // namespace igabde

#endif
