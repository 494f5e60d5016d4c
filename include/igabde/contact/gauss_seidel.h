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
     * @brief Whether a sweep solves every pair's local problem of @p data in
     * closed form (solve_local_pair(): 2D, or frictionless with one
     * component), so that a sweep is one pass over W's non-zeros. In 3D
     * with friction a slipping pair takes a local Newton. The Gauss-Seidel
     * phases are chosen by it: up to a thousand first sweeps, and the
     * sweeps after the Newton phases (BNewtonSolver).
     */
    inline bool
    local_problems_in_closed_form(const ContactData &data)
    {
      return data.n_components <= 2;
    }

    /**
     * @brief The local problem of one pair in 3D (solve_local_pair()'s
     * conventions) where its solution is open or sticks, in closed form:
     * p = 0 if c_n >= 0; else p = -A^{-1} c if that p has p_n >= 0 and
     * |p_t| <= mu p_n. The slip branch has no closed form (its direction
     * solves a nonlinear equation where A couples the tangents):
     * solve_local_pair_law() takes it.
     * @param A The pair's diagonal block of W (row-major, 3 x 3).
     * @return false (p untouched) if neither branch holds or A is not
     * positive definite.
     */
    bool
    solve_local_pair_open_or_stick(const double *A,
                                   const double *c,
                                   const double  mu,
                                   double       *p);

    /**
     * @brief The local problem of one pair in any dimension, H(p) = 0 for
     * the pair's law @p law (pair @p c of @p data) at u = A p + c_u: a
     * damped semismooth Newton on the pair's three (or two, one) unknowns,
     * whose matrix is the law's piece, dH = A_piece du + B_piece dp, with
     * du = A dp; from the pair's current @p p. Used where the branches
     * have no closed form (3D friction: the slip direction).
     * @param A The pair's diagonal block of W (row-major, d x d).
     * @return false if it does not converge in 30 steps or a step finds no
     * decrease (the pair's p is then left as it was).
     */
    bool
    solve_local_pair_law(const PairLawModel &law,
                         const ContactData  &data,
                         const unsigned int  c,
                         const double       *A,
                         const double       *c_u,
                         double             *p);

    /** @brief How a Gauss-Seidel phase runs. */
    struct GaussSeidelOptions
    {
      /// Sweeps at most.
      unsigned int max_sweeps = 2000;
      /// The stopping test every this many sweeps.
      unsigned int check_every = 10;
      /// Whether the iterates are offered to the driver as its best.
      bool offer_best = true;
      /**
       * Whether the phase ends as soon as the error's rate per sweep since
       * the last check, kept up to max_sweeps, would not reach the
       * tolerance (a first try that is to cost little where it does not
       * succeed). From the third check on, the next check then comes where
       * that rate reaches the tolerance, after at most as many sweeps as
       * were done (a check costs more than a sweep).
       */
      bool quit_when_too_slow = false;
    };

    /**
     * @brief The nonsmooth Gauss-Seidel phase (NSGS; Jean and Moreau's
     * method, Siconos' NSGS) on u = W p + q: sweeps over the pairs, each
     * pair's p solved with the others' forces fixed (2D and frictionless:
     * exactly, solve_local_pair(); 3D: open and stick exactly,
     * solve_local_pair_open_or_stick(), slip by solve_local_pair_law()). With a
     * dense W, u is kept and updated by the pair's columns (O(n) per pair,
     * O(n^2) per sweep); with a sparse W (@p Ws), the pair's u is read
     * from its rows (a sweep is one pass over W's non-zeros). Slow
     * (linear) but monotone on symmetric positive definite W where
     * Newton's active sets cycle, and fast where W is nearly block
     * diagonal (stacks of rigid bodies). The error is measured with the
     * driver's stopping test every options.check_every sweeps; the phase
     * ends when it passes, after options.max_sweeps sweeps, at the time
     * limit, or when the error has not halved in 100 sweeps (stall). No
     * floating bodies.
     * @param W The dense W (its diagonal blocks are read in both cases).
     * @param Ws W in compressed rows, or nullptr.
     * @param x The start (the driver's best iterate), the result on return.
     * @param sweeps The sweeps done.
     */
    PhaseOutcome
    gauss_seidel_phase(NewtonDriver          &driver,
                       const ContactData     &data,
                       const PairLawModel    &law,
                       const Eigen::MatrixXd &W,
                       const Eigen::SparseMatrix<double, Eigen::RowMajor> *Ws,
                       ContactIterate                                     &x,
                       const GaussSeidelOptions &options,
                       unsigned int             &sweeps);
  } // namespace contact
} // namespace igabde

#endif
