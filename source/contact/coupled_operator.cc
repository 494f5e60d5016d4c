#include <igabde/contact/coupled_operator.h>
#include <igabde/contact/newton_driver.h>

#include <algorithm>

namespace igabde
{
  namespace contact
  {
    using Vec = Eigen::VectorXd;



    std::string
    CoupledOperator::path_name() const
    {
      return "full";
    }



    Vec
    CoupledOperator::displacement(const Vec &p, const Vec &w) const
    {
      Vec u = apply_C(w);
      if (eps > 0.)
        u += eps * p;
      return u;
    }



    void
    CoupledOperator::displacement_adjoint(const Vec &y,
                                          Vec       &y_p,
                                          Vec       &y_w) const
    {
      // C^T y is minus the force part of the linearised displacement
      // equations.
      y_w = -tangent_equations(Vec::Zero(n_dofs()), y);
      y_p = eps * y;
    }



    Vec
    CoupledOperator::equilibrium_residual(const Vec &p, const Vec &w) const
    {
      return displacement_equations(w, p);
    }



    void
    CoupledOperator::equilibrium_adjoint(const Vec &h, Vec &h_p, Vec &h_w) const
    {
      // E = K w - C^T p: E_w^T h = K^T h (held rows identity; K_T at
      // finite strain), E_p^T h = -C h.
      h_w = tangent_transpose(h);
      h_p = -apply_C(h);
    }



    bool
    CoupledOperator::equilibrium_is_linear() const
    {
      return !finite_strain();
    }



    void
    CoupledOperator::linearize(const ContactIterate &x)
    {
      linearize_bodies(x.w);
      linearize_geometry(x);
    }



    Vec
    CoupledOperator::displacement_derivative(const Vec &v_p,
                                             const Vec &v_w) const
    {
      Vec u = apply_C_derivative(v_w);
      if (eps > 0.)
        u += eps * v_p;
      return u;
    }



    Vec
    CoupledOperator::equilibrium_derivative(const Vec &v_p,
                                            const Vec &v_w) const
    {
      return tangent_equations(v_w, v_p);
    }



    double
    CoupledOperator::equilibrium_scale(const Vec &p, const Vec &w) const
    {
      return displacement_equations_scale(w, p);
    }



    PairWeights
    CoupledOperator::weights(const ContactData &, const double factor) const
    {
      // No W: the stiffness of the underlying elements is the scale (any
      // r > 0 gives the same solution set).
      PairWeights w;
      w.r_n = factor * element_pair_stiffness();
      w.r_t = w.r_n;
      return w;
    }



    Vec
    CoupledOperator::pair_stiffness() const
    {
      return element_pair_stiffness();
    }



    double
    CoupledOperator::flexibility_scale() const
    {
      double scale = 0.;
      for (const double k : element_pair_stiffness())
        if (k > 0.)
          scale = std::max(scale, 1. / k);
      return scale;
    }



    void
    CoupledOperator::set_proximal_shift(const double shift)
    {
      eps = shift;
    }



    bool
    CoupledOperator::newton_step(const ContactData    &data,
                                 const NewtonBlocks   &blocks,
                                 const ContactIterate &F,
                                 ContactIterate       &dx,
                                 StepReport           &report,
                                 const double,
                                 const bool,
                                 const double linear_tolerance)
    {
      std::vector<Eigen::Matrix3d> A(blocks.size()), B(blocks.size());
      for (unsigned int c = 0; c < blocks.size(); ++c)
        {
          A[c] = blocks[c].A;
          // The proximal shift: d/dp of A (u + eps p) + B p.
          B[c] = blocks[c].B + eps * blocks[c].A;
        }
      factorize(A, B);
      const Vec  r_alpha       = data.n_alpha() > 0 ? Vec(-F.alpha) : Vec();
      const bool ok            = solve(-F.w,
                            -F.p,
                            r_alpha,
                            dx.w,
                            dx.p,
                            dx.alpha,
                            report.why,
                            linear_tolerance);
      report.linear_iterations = linear_iterations();
      report.n_reduced         = n_dofs() + n_rows() + data.n_alpha();
      if (dx.alpha.size() == 0)
        dx.alpha = Vec::Zero(data.n_alpha());
      if (ok && !(dx.w.allFinite() && dx.p.allFinite() && dx.alpha.allFinite()))
        {
          report.why = "the Newton system gave a non-finite increment "
                       "(singular matrix)";
          return false;
        }
      return ok;
    }



    bool
    CoupledOperator::bilateral_start(const ContactData       &data,
                                     const std::vector<bool> &closed,
                                     ContactIterate          &x)
    {
      // The pairs expected closed glued (u_c = 0), the others free of
      // force: one solve of the Newton system with the glued blocks.
      if (std::find(closed.begin(), closed.end(), true) == closed.end())
        return false;
      const unsigned int           m = data.n_components;
      const Vec                   &k = element_pair_stiffness();
      std::vector<Eigen::Matrix3d> A(data.n_contacts, Eigen::Matrix3d::Zero()),
        B(data.n_contacts, Eigen::Matrix3d::Zero());
      Vec r_p = Vec::Zero(data.n_rows());
      // With finite sliding the pairs at w = 0, where this start is
      // linearised, and their gaps.
      ContactIterate zero;
      zero.p = Vec::Zero(data.n_rows());
      zero.w = Vec::Zero(n_dofs());
      update_geometry(zero);
      const Vec q = displacement_offset() != nullptr ?
                      Vec(data.q + *displacement_offset()) :
                      data.q;
      // Directions held by supports on both sides carry no force, as in the
      // solver: a glued one would be a zero row.
      std::vector<bool> held;
      held_pair_directions(data, *this, held);
      for (unsigned int i = 0; i < data.n_contacts; ++i)
        for (unsigned int s = 0; s < m; ++s)
          if (closed[i] && !held[m * i + s])
            {
              A[i](s, s)     = k[i];
              r_p[m * i + s] = -k[i] * q[m * i + s];
            }
          else
            B[i](s, s) = 1.;
      std::string why;
      // At finite strain one Newton step of the glued system from w = 0
      // (the reference of set_reference(), where the system is linearised).
      const Vec r_w = finite_strain() ?
                        Vec(-displacement_equations(Vec::Zero(n_dofs()),
                                                    Vec::Zero(n_rows()))) :
                        Vec(Vec::Zero(n_dofs()));
      factorize(A, B);
      if (!solve(r_w,
                 r_p,
                 data.n_alpha() > 0 ? Vec(data.b) : Vec(),
                 x.w,
                 x.p,
                 x.alpha,
                 why) ||
          !x.p.allFinite() || !x.w.allFinite())
        return false;
      if (x.alpha.size() == 0)
        x.alpha = Vec::Zero(data.n_alpha());
      return true;
    }
  } // namespace contact
} // namespace igabde
