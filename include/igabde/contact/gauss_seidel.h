#ifndef igabde_contact_gauss_seidel_h
#define igabde_contact_gauss_seidel_h

#include <igabde/contact/newton_driver.h>

#include <Eigen/Dense>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The local problem of one pair in 2D (or frictionless): p with
     * u = A p + c, u_n >= 0, p_n >= 0, u_n p_n = 0 and Coulomb's law
     * |p_t| <= mu p_n, p_t = -mu p_n sign(u_t) where u_t != 0 (ContactData's
     * conventions), solved exactly by trying its branches in turn: open
     * (p = 0, if c_n >= 0), stick (A p = -c), slip in either direction
     * (u_n = 0, p_t = -s mu p_n, s u_t >= 0).
     * @param n_components 1 (frictionless: A and c are 1 x 1) or 2.
     * @param A The pair's diagonal block of W (row-major, n x n).
     * @return false if no branch holds (A not positive on the cone: the
     * pair's p is then left as it was).
     */
    bool
    solve_local_pair(const unsigned int n_components,
                     const double      *A,
                     const double      *c,
                     const double       mu,
                     double            *p);

    /**
     * @brief The nonsmooth Gauss-Seidel phase (NSGS; Jean and Moreau's
     * method, Siconos' FC2D_NSGS) on u = W p + q: sweeps over the pairs,
     * each pair's p solved exactly (solve_local_pair()) with the others'
     * forces fixed, u updated by that pair's columns of W (O(n) per pair,
     * O(n^2) per sweep). Slow (linear) but monotone on symmetric positive
     * definite W where Newton's active sets cycle. The error is measured
     * with the driver's stopping test every ten sweeps; the phase ends when
     * it passes, after @p max_sweeps sweeps, at the time limit, or when the
     * error has not halved in 100 sweeps (stall). 2D friction or
     * frictionless, no floating bodies.
     * @param x The start (the driver's best iterate), the result on return.
     * @param sweeps The sweeps done.
     */
    PhaseOutcome
    gauss_seidel_phase(NewtonDriver          &driver,
                       const ContactData     &data,
                       const PairLawModel    &law,
                       const Eigen::MatrixXd &W,
                       ContactIterate        &x,
                       const unsigned int     max_sweeps,
                       unsigned int          &sweeps);
  } // namespace contact
} // namespace igabde

#endif
