#include <igabde/contact/newton_driver.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace igabde
{
  namespace contact
  {
    using Vec = Eigen::VectorXd;



    BdeLaw::BdeLaw(const PairWeights   &weights,
                   const PairWeights   &unit_weights,
                   const FrictionRadius radius)
      : w(weights)
      , unit(unit_weights)
      , radius(radius)
    {}



    void
    BdeLaw::evaluate(const ContactData &data,
                     const unsigned int c,
                     const double      *p,
                     const double      *u,
                     double            *H,
                     PairPiece         *piece) const
    {
      const unsigned int d = data.n_components;
      pair_law(d,
               d > 1 ? data.mu[c] : 0.,
               w.r_n[c],
               w.r_t[c],
               radius,
               p,
               u,
               H,
               piece);
    }



    void
    BdeLaw::tie_rule(const ContactData &data,
                     const Vec         &p,
                     const Vec         &u,
                     NewtonBlocks      &pieces) const
    {
      if (data.n_alpha() == 0 || data.n_contacts == 0)
        return;
      for (const PairPiece &piece : pieces)
        if (piece.closed)
          return;
      const unsigned int d    = data.n_components;
      unsigned int       best = 0;
      double             gap  = std::numeric_limits<double>::infinity();
      for (unsigned int c = 0; c < data.n_contacts; ++c)
        {
          const double g = w.r_n[c] * u[c * d] - p[c * d];
          if (g < gap)
            {
              gap  = g;
              best = c;
            }
        }
      PairPiece &piece = pieces[best];
      piece.closed     = true;
      piece.A(0, 0)    = w.r_n[best];
      piece.B(0, 0)    = 0.;
    }



    void
    BdeLaw::errors(const ContactData &data,
                   const Vec         &p,
                   const Vec         &u,
                   const Vec &,
                   double &err,
                   double &balanced) const
    {
      err      = relative_natural_map_error(data, p, u);
      balanced = balanced_natural_map_error(data, unit, p, u);
    }



    PenaltyLaw::PenaltyLaw(const Vec &k_n, const Vec &k_t, const Vec &lambda)
      : k_n(k_n)
      , k_t(k_t)
      , lambda(lambda)
    {}



    void
    PenaltyLaw::evaluate(const ContactData &data,
                         const unsigned int c,
                         const double      *p,
                         const double      *u,
                         double            *H,
                         PairPiece         *piece) const
    {
      const unsigned int d = data.n_components;
      double             P[3];
      const PairPiece    result = penalty_law(d,
                                           d > 1 ? data.mu[c] : 0.,
                                           k_n[c],
                                           k_t[c],
                                           lambda.data() + c * d,
                                           u,
                                           P);
      for (unsigned int k = 0; k < d; ++k)
        H[k] = p[k] - P[k];
      if (piece)
        *piece = result;
    }



    void
    PenaltyLaw::tie_rule(const ContactData &data,
                         const Vec         &p,
                         const Vec         &u,
                         NewtonBlocks      &pieces) const
    {
      // A pair that carries compression while touching to rounding (the
      // bilateral start, or the previous step, glues the pairs it expects
      // closed at u_n = 0) takes the closed piece: else a floating body
      // could start with every pair open and a singular Newton matrix.
      const unsigned int d = data.n_components;
      for (unsigned int c = 0; c < data.n_contacts; ++c)
        {
          const double pn = p[c * d], un = u[c * d];
          if (pieces[c].status != ContactStatus::open || !(pn > 0.) ||
              !(un > 0.) || k_n[c] * un > 1e-8 * pn)
            continue;
          double glued[3] = {0.,
                             d > 1 ? u[c * d + 1] : 0.,
                             d > 2 ? u[c * d + 2] : 0.};
          double P[3];
          pieces[c] = penalty_law(d,
                                  d > 1 ? data.mu[c] : 0.,
                                  k_n[c],
                                  k_t[c],
                                  lambda.data() + c * d,
                                  glued,
                                  P);
        }
    }



    void
    PenaltyLaw::errors(const ContactData &data,
                       const Vec         &p,
                       const Vec &,
                       const Vec &H,
                       double    &err,
                       double    &balanced) const
    {
      // |H| relative to the force scale: the penalty forces P = p - H, or
      // the loads floating bodies balance.
      double scale = (p - H).norm();
      if (data.n_alpha() > 0)
        scale = std::max(scale, data.b.norm());
      err      = H.norm() / (scale > 0. ? scale : 1.);
      balanced = err;
    }



    double
    PenaltyLaw::floor_factor() const
    {
      // The rounding floor of the penalty residual grows with the
      // condition of K (and of the penalty): once it stops halving, 1000
      // times the tolerance is accepted (the augmented Lagrangian's outer
      // test still measures the natural map).
      return 1e3;
    }



    bool
    PenaltyLaw::full_step_on_failure() const
    {
      // A penalty Newton step that no backtracking accepts is taken whole
      // (the pair states still change; ANSYS takes full steps always).
      return true;
    }



  } // namespace contact
} // namespace igabde
