#include <igabde/contact/newton_driver.h>

#include <algorithm>
#include <utility>

namespace igabde
{
  namespace contact
  {
    using Vec = Eigen::VectorXd;



    BdeLaw::BdeLaw(PairWeights          weights,
                   PairWeights          unit_weights,
                   const FrictionRadius radius)
      : w(std::move(weights))
      , unit(std::move(unit_weights))
      , unit_is_w(false)
      , radius(radius)
    {}



    BdeLaw::BdeLaw(PairWeights unit_weights, const FrictionRadius radius)
      : w(std::move(unit_weights))
      , unit_is_w(true)
      , radius(radius)
    {}



    const PairWeights &
    BdeLaw::unit_weights() const
    {
      return unit_is_w ? w : unit;
    }



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



    namespace
    {
      /**
       * An orthonormal basis of the rows of G (columns scaled to unit
       * length) that the Newton matrix ties down; add() says whether a row
       * enlarges it.
       */
      class RowSpace
      {
      public:
        explicit RowSpace(const Eigen::MatrixXd &G)
          : G(G)
          , scale(G.cols())
        {
          for (Eigen::Index a = 0; a < G.cols(); ++a)
            {
              const double norm = G.col(a).norm();
              scale(a)          = norm > 0. ? 1. / norm : 1.;
            }
        }

        bool
        add(const unsigned int row)
        {
          Vec          r      = G.row(row).transpose().cwiseProduct(scale);
          const double length = r.norm();
          for (const Vec &e : basis)
            r -= e.dot(r) * e;
          if (!(r.norm() > 1e-8 * length))
            return false;
          basis.push_back(r / r.norm());
          return true;
        }

        bool
        full() const
        {
          return basis.size() == static_cast<std::size_t>(G.cols());
        }

      private:
        const Eigen::MatrixXd &G;
        Vec                    scale;
        std::vector<Vec>       basis;
      };
    } // namespace



    void
    BdeLaw::tie_rule(const ContactData &data,
                     const Vec         &p,
                     const Vec         &u,
                     NewtonBlocks      &pieces) const
    {
      // The alpha columns of the Newton matrix are tied down by the rows of
      // G whose pair equation fixes u: the normal rows of closed pairs and
      // the tangential rows of sticking ones. Until these span every
      // column, the pairs closest to closing (smallest r_n u_n - p_n) take
      // the closed branch, and then, if a tangential mode is still free,
      // closed pairs the stick branch: else a floating body starts with a
      // singular Newton matrix whenever the one closest pair cannot hold
      // all its modes (a half disc whose lowest point falls between two
      // pairs rolls about them).
      if (data.n_alpha() == 0 || data.n_contacts == 0)
        return;
      const unsigned int d = data.n_components;
      RowSpace           rows(data.G);
      for (unsigned int c = 0; c < data.n_contacts; ++c)
        {
          if (pieces[c].closed)
            rows.add(c * d);
          if (pieces[c].status == ContactStatus::stick)
            for (unsigned int k = 1; k < d; ++k)
              rows.add(c * d + k);
        }
      if (rows.full())
        return;
      std::vector<unsigned int> order(data.n_contacts);
      for (unsigned int c = 0; c < data.n_contacts; ++c)
        order[c] = c;
      std::stable_sort(order.begin(),
                       order.end(),
                       [&](const unsigned int a, const unsigned int b) {
                         return w.r_n[a] * u[a * d] - p[a * d] <
                                w.r_n[b] * u[b * d] - p[b * d];
                       });
      for (const unsigned int c : order)
        {
          if (rows.full())
            return;
          PairPiece &piece = pieces[c];
          if (!piece.closed && rows.add(c * d))
            {
              piece.closed  = true;
              piece.A(0, 0) = w.r_n[c];
              piece.B(0, 0) = 0.;
            }
        }
      for (const unsigned int c : order)
        {
          if (rows.full())
            return;
          PairPiece &piece = pieces[c];
          if (!piece.closed || piece.status == ContactStatus::stick)
            continue;
          bool tangential = false;
          for (unsigned int k = 1; k < d; ++k)
            tangential = rows.add(c * d + k) || tangential;
          if (tangential)
            for (unsigned int k = 1; k < d; ++k)
              {
                piece.A.row(k).setZero();
                piece.B.row(k).setZero();
                piece.A(k, k) = w.r_t[c];
              }
        }
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
      balanced = balanced_natural_map_error(data, unit_weights(), p, u);
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
