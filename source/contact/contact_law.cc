#include <igabde/contact/contact_law.h>

#include <algorithm>
#include <cmath>

namespace igabde
{
  namespace contact
  {
    std::string
    to_string(const ContactStatus status)
    {
      switch (status)
        {
          case ContactStatus::open:
            return "open";
          case ContactStatus::stick:
            return "stick";
          case ContactStatus::slip:
            return "slip";
          case ContactStatus::closed:
            return "closed";
        }
      return "unknown";
    }



    void
    project_on_cone(double *x, const unsigned int d, const double mu)
    {
      double nt = 0.;
      for (unsigned int k = 1; k < d; ++k)
        nt += x[k] * x[k];
      nt = std::sqrt(nt);
      if (nt <= mu * x[0])
        return;
      if (mu * nt <= -x[0])
        {
          for (unsigned int k = 0; k < d; ++k)
            x[k] = 0.;
          return;
        }
      const double xn = (x[0] + mu * nt) / (1. + mu * mu);
      x[0]            = xn;
      for (unsigned int k = 1; k < d; ++k)
        x[k] *= mu * xn / nt;
    }



    PairWeights
    pair_weights(const Eigen::MatrixXd &W,
                 const unsigned int     n_components,
                 const double           factor,
                 const double           shift)
    {
      // The weights of W + shift I (the proximal phase's subproblems).
      const unsigned int d  = n_components;
      const unsigned int nc = d > 0 ? W.rows() / d : 0;
      PairWeights        w;
      w.r_n.resize(nc);
      w.r_t.resize(nc);
      double max_diag = 0.;
      if (W.rows() > 0)
        max_diag = W.diagonal().maxCoeff() + shift;
      const double fallback = max_diag > 0. ? factor / max_diag : factor;
      for (unsigned int c = 0; c < nc; ++c)
        {
          const unsigned int o   = c * d;
          const double       wnn = W(o, o) + shift;
          w.r_n[c] =
            (wnn > 1e-14 * max_diag && wnn > 0.) ? factor / wnn : fallback;
          double lmax = 0.;
          if (d == 2)
            lmax = W(o + 1, o + 1) + shift;
          else if (d == 3)
            {
              const double a = W(o + 1, o + 1) + shift,
                           b = W(o + 2, o + 2) + shift,
                           e = 0.5 * (W(o + 1, o + 2) + W(o + 2, o + 1));
              lmax =
                0.5 * (a + b) + std::sqrt(0.25 * (a - b) * (a - b) + e * e);
            }
          w.r_t[c] =
            (lmax > 1e-14 * max_diag && lmax > 0.) ? factor / lmax : w.r_n[c];
        }
      return w;
    }



    PairPiece
    penalty_law(const unsigned int d,
                const double       mu,
                const double       k_n,
                const double       k_t,
                const double      *lambda,
                const double      *u,
                double            *p)
    {
      PairPiece piece;
      piece.B.setIdentity();
      for (unsigned int k = 0; k < d; ++k)
        p[k] = 0.;
      const double pn = lambda[0] - k_n * u[0];
      if (!(pn >= 0.))
        {
          piece.status = ContactStatus::open;
          return piece;
        }
      piece.closed  = true;
      p[0]          = pn;
      piece.A(0, 0) = k_n;
      if (d == 1)
        {
          piece.status = ContactStatus::closed;
          return piece;
        }
      double trial[3] = {0., 0., 0.}, norm = 0.;
      for (unsigned int k = 1; k < d; ++k)
        {
          trial[k] = lambda[k] - k_t * u[k];
          norm += trial[k] * trial[k];
        }
      norm           = std::sqrt(norm);
      const double R = mu * pn;
      if (norm <= R)
        {
          piece.status = mu > 0. ? ContactStatus::stick : ContactStatus::closed;
          for (unsigned int k = 1; k < d; ++k)
            {
              p[k]          = trial[k];
              piece.A(k, k) = k_t;
            }
          return piece;
        }
      piece.status = mu > 0. ? ContactStatus::slip : ContactStatus::closed;
      const double ratio = R / norm;
      for (unsigned int k = 1; k < d; ++k)
        {
          const double tk = trial[k] / norm;
          p[k]            = R * tk;
          piece.A(k, 0)   = mu * k_n * tk;
          for (unsigned int l = 1; l < d; ++l)
            piece.A(k, l) =
              k_t * ratio * ((k == l ? 1. : 0.) - tk * trial[l] / norm);
        }
      return piece;
    }



    void
    pair_law(const unsigned int   d,
             const double         mu,
             const double         rn,
             const double         rt,
             const FrictionRadius radius,
             const double        *x,
             const double        *u,
             double              *H,
             PairPiece           *br)
    {
      const double pn     = x[0];
      const double run    = rn * u[0];
      const bool   closed = run < pn;
      H[0]                = closed ? run : pn;
      if (br)
        {
          br->A.setZero();
          br->B.setZero();
          br->closed = closed;
          if (closed)
            br->A(0, 0) = rn;
          else
            br->B(0, 0) = 1.;
          br->status = !closed          ? ContactStatus::open :
                       d > 1 && mu > 0. ? ContactStatus::slip :
                                          ContactStatus::closed;
        }
      if (d == 1)
        return;

      const double R    = radius == FrictionRadius::christensen_pang ?
                            mu * std::max(pn, 0.) :
                            mu * std::max(pn - run, 0.);
      double       z[2] = {0., 0.};
      double       nz   = 0.;
      for (unsigned int k = 1; k < d; ++k)
        {
          z[k - 1] = x[k] - rt * u[k];
          nz += z[k - 1] * z[k - 1];
        }
      nz = std::sqrt(nz);
      if (nz <= R)
        {
          // stick, lambda := 1 (includes z = 0, R = 0)
          for (unsigned int k = 1; k < d; ++k)
            H[k] = rt * u[k];
          if (br)
            {
              for (unsigned int k = 1; k < d; ++k)
                br->A(k, k) = rt;
              if (closed && mu > 0.)
                br->status = ContactStatus::stick;
            }
        }
      else if (R <= 0.)
        {
          // projection onto {0}: H_t = p_t
          for (unsigned int k = 1; k < d; ++k)
            H[k] = x[k];
          if (br)
            for (unsigned int k = 1; k < d; ++k)
              br->B(k, k) = 1.;
        }
      else
        {
          const double lambda = R / nz;
          for (unsigned int k = 1; k < d; ++k)
            H[k] = x[k] - lambda * z[k - 1];
          if (br)
            {
              // Gamma = lambda (I - zhat zhat^T)
              for (unsigned int k = 1; k < d; ++k)
                for (unsigned int l = 1; l < d; ++l)
                  {
                    const double zz    = (z[k - 1] / nz) * (z[l - 1] / nz);
                    const double gamma = lambda * ((k == l ? 1. : 0.) - zz);
                    br->B(k, l)        = (k == l ? 1. : 0.) - gamma;
                    br->A(k, l)        = rt * gamma;
                  }
              for (unsigned int k = 1; k < d; ++k)
                {
                  br->B(k, 0) = -mu * z[k - 1] / nz;
                  if (radius == FrictionRadius::alart_curnier)
                    br->A(k, 0) = mu * rn * z[k - 1] / nz;
                }
            }
        }
    }



    double
    natural_map_error(const ContactData     &problem,
                      const Eigen::VectorXd &p,
                      const Eigen::VectorXd &u)
    {
      const unsigned int d   = problem.n_components;
      double             sum = 0.;
      double             y[3], e;
      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        {
          const unsigned int o = c * d;
          if (d == 1)
            {
              e = p[o] - std::max(0., p[o] - u[o]);
              sum += e * e;
              continue;
            }
          const double mu = problem.mu[c];
          double       ut = 0.;
          for (unsigned int k = 1; k < d; ++k)
            ut += u[o + k] * u[o + k];
          ut = std::sqrt(ut);
          for (unsigned int k = 0; k < d; ++k)
            y[k] = p[o + k] - u[o + k];
          y[0] -= mu * ut;
          project_on_cone(y, d, mu);
          for (unsigned int k = 0; k < d; ++k)
            {
              e = p[o + k] - y[k];
              sum += e * e;
            }
        }
      return std::sqrt(sum);
    }



    double
    relative_natural_map_error(const ContactData     &problem,
                               const Eigen::VectorXd &p,
                               const Eigen::VectorXd &u)
    {
      const double err = natural_map_error(problem, p, u);
      const double norm_q =
        std::max(problem.q.norm(), problem.displacement_scale);
      const double norm_r = (u - problem.q).norm();
      if (norm_q > 0. && norm_q > 1e-12 * norm_r)
        return err / norm_q;
      const double norm_p = p.norm();
      return norm_p > 0. ? err / norm_p : err;
    }



    double
    relative_equilibrium_error(const ContactData     &problem,
                               const Eigen::VectorXd &p,
                               double                &absolute)
    {
      absolute = 0.;
      if (problem.n_alpha() == 0)
        return 0.;
      absolute          = (problem.G.transpose() * p - problem.b).norm();
      const double den1 = problem.b.norm();
      const double den2 =
        (problem.G.cwiseAbs().transpose() * p.cwiseAbs()).norm();
      const double den = std::max(den1, den2);
      return den > 0. ? absolute / den : absolute;
    }



    double
    balanced_natural_map_error(const ContactData     &problem,
                               const PairWeights     &weights,
                               const Eigen::VectorXd &p,
                               const Eigen::VectorXd &u)
    {
      const unsigned int d   = problem.n_components;
      double             sum = 0., sum_q = 0., sum_p = 0.;
      double             y[3], x[3], e;
      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        {
          const unsigned int o   = c * d;
          const double       rho = weights.r_n[c];
          const double       mu  = d > 1 ? problem.mu[c] : 0.;
          double             ut  = 0.;
          for (unsigned int k = 1; k < d; ++k)
            ut += u[o + k] * u[o + k];
          ut = std::sqrt(ut);
          for (unsigned int k = 0; k < d; ++k)
            {
              x[k] = rho * u[o + k];
              sum_q += rho * rho * problem.q[o + k] * problem.q[o + k];
              sum_p += p[o + k] * p[o + k];
            }
          x[0] += rho * mu * ut;
          for (unsigned int k = 0; k < d; ++k)
            y[k] = p[o + k] - x[k];
          if (d == 1)
            y[0] = std::max(y[0], 0.);
          else
            project_on_cone(y, d, mu);
          for (unsigned int k = 0; k < d; ++k)
            {
              e = p[o + k] - y[k];
              sum += e * e;
            }
        }
      const double err = std::sqrt(sum);
      const double nq = std::sqrt(sum_q), np = std::sqrt(sum_p);
      double       nr = 0.; // |rho (u - q)|, to detect q ~ 0
      for (unsigned int i = 0; i < problem.n_rows(); ++i)
        {
          const double v = weights.r_n[i / d] * (u[i] - problem.q[i]);
          nr += v * v;
        }
      nr = std::sqrt(nr);
      if (nq > 0. && nq > 1e-12 * nr)
        return err / nq;
      return np > 0. ? err / np : err;
    }


  } // namespace contact
} // namespace igabde
