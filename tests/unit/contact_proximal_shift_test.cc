// The proximal phase's subproblems use W + eps I. CondensedOperator adds
// the shift where W is read instead of copying W; the reference here is a
// second operator built on the explicit matrix W + eps I. Both must give
// the same products, weights, stiffnesses and Newton directions, on the
// dense and the sparse linear algebra, with symmetric (Cholesky) and
// unsymmetric (LU) Newton matrices, with and without floating modes.

#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_operator.h>
#include <igabde/contact/contact_problem.h>

#include <gtest/gtest.h>

#include <random>
#include <string>

using namespace igabde::contact;

namespace proximal_shift_test
{
  using Vec = Eigen::VectorXd;
  using Mat = Eigen::MatrixXd;

  // A symmetric positive semi-definite W of rank 7 on 5 pairs in 3D with
  // a quarter of its entries exactly zero (a block pattern, as rigid
  // bodies give): singular without the shift, as the proximal phase
  // meets it.
  Mat
  semidefinite_flexibility()
  {
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    Mat                                    H(15, 7);
    for (int i = 0; i < 15; ++i)
      for (int j = 0; j < 7; ++j)
        H(i, j) = ((i / 3 + j) % 4 == 3) ? 0. : uniform(rng);
    return H * H.transpose();
  }

  // One piece per pair: closed and sticking (A = r I), slipping (coupled
  // B), open (trivial rows), closed and sticking again, and a normal-only
  // closed pair with free tangents.
  NewtonBlocks
  mixed_pieces()
  {
    NewtonBlocks pieces(5);
    pieces[0].A = 0.7 * Eigen::Matrix3d::Identity();
    pieces[1].A.setZero();
    pieces[1].A(0, 0) = 0.7;
    pieces[1].A(1, 1) = 0.2;
    pieces[1].B       = Eigen::Matrix3d::Identity();
    pieces[1].B(0, 0) = 0.;
    pieces[1].B(1, 0) = -0.3;
    pieces[1].B(2, 1) = 0.1;
    pieces[2].B       = Eigen::Matrix3d::Identity();
    pieces[3].A       = 1.3 * Eigen::Matrix3d::Identity();
    pieces[4].A(0, 0) = 0.9;
    pieces[4].B       = Eigen::Matrix3d::Identity();
    pieces[4].B(0, 0) = 0.;
    return pieces;
  }

  double
  relative(const Vec &a, const Vec &b)
  {
    return (a - b).norm() / std::max(b.norm(), 1e-300);
  }

  void
  check_same_operator(const Mat                             &W,
                      const double                           eps,
                      const CondensedOperator::LinearAlgebra la,
                      const ContactData                     &data,
                      const NewtonBlocks                    &pieces)
  {
    const Mat         W_eps = W + eps * Mat::Identity(W.rows(), W.cols());
    CondensedOperator shifted(W, la, 0.9);
    CondensedOperator reference(W_eps, la, 0.9);
    shifted.set_proximal_shift(eps);

    std::mt19937                           rng(11);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    Vec                                    p(W.rows());
    for (int i = 0; i < p.size(); ++i)
      p[i] = uniform(rng);

    // Products (before and after the structure is built by a step).
    EXPECT_LE(relative(shifted.displacement(p, Vec()),
                       reference.displacement(p, Vec())),
              1e-14);
    const PairWeights ws = shifted.weights(data, 0.5),
                      wr = reference.weights(data, 0.5);
    EXPECT_LE(relative(ws.r_n, wr.r_n), 1e-14);
    EXPECT_LE(relative(ws.r_t, wr.r_t), 1e-14);
    EXPECT_LE(relative(shifted.pair_stiffness(), reference.pair_stiffness()),
              1e-14);

    ContactIterate F;
    F.p = Vec(W.rows());
    for (int i = 0; i < F.p.size(); ++i)
      F.p[i] = uniform(rng);
    F.alpha = Vec::Constant(data.n_alpha(), 0.25);
    ContactIterate              ds, dr;
    ContactOperator::StepReport rs, rr;
    ASSERT_TRUE(shifted.newton_step(data, pieces, F, ds, rs, 1e-12, true, 0.));
    ASSERT_TRUE(
      reference.newton_step(data, pieces, F, dr, rr, 1e-12, true, 0.));
    // Regular with the shift: no Levenberg-Marquardt step on either side.
    EXPECT_EQ(rs.note.find("lm"), std::string::npos) << rs.note;
    EXPECT_EQ(rr.note.find("lm"), std::string::npos) << rr.note;
    EXPECT_EQ(rs.n_reduced, rr.n_reduced);
    // The same factorisation of matrices that agree to rounding (1e-16
    // relative): the directions agree to the reduced matrix's condition
    // number times that. The shift (5 % of W's largest diagonal entry)
    // keeps the condition number moderate; 1e-10 allows it up to 1e6.
    EXPECT_LE(relative(ds.p, dr.p), 1e-10);
    if (data.n_alpha() > 0)
      {
        EXPECT_LE(relative(ds.alpha, dr.alpha), 1e-10);
      }

    Vec ys, yr, ws_, wr_;
    shifted.displacement_adjoint(p, ys, ws_);
    reference.displacement_adjoint(p, yr, wr_);
    EXPECT_LE(relative(ys, yr), 1e-14);
    EXPECT_LE(relative(shifted.displacement(p, Vec()),
                       reference.displacement(p, Vec())),
              1e-14);

    // The shift taken off again: the operator of W itself.
    shifted.set_proximal_shift(0.);
    const CondensedOperator plain(W, la, 0.9);
    EXPECT_LE(relative(shifted.displacement(p, Vec()),
                       plain.displacement(p, Vec())),
              1e-14);
    EXPECT_LE(relative(shifted.pair_stiffness(), plain.pair_stiffness()),
              1e-14);
  }
} // namespace proximal_shift_test



TEST(ContactProximalShift, InPlaceShiftIsTheShiftedMatrix)
{
  using namespace proximal_shift_test;
  const Mat   W = semidefinite_flexibility();
  ContactData data;
  data.n_contacts   = 5;
  data.n_components = 3;
  data.q            = Vec::Zero(15);
  data.mu.assign(5, 0.3);
  const double eps = 0.05 * W.diagonal().maxCoeff();
  for (const auto la : {CondensedOperator::LinearAlgebra::dense,
                        CondensedOperator::LinearAlgebra::sparse})
    {
      SCOPED_TRACE(la == CondensedOperator::LinearAlgebra::dense ? "dense" :
                                                                   "sparse");
      // Mixed pieces: an unsymmetric reduced matrix (LU).
      check_same_operator(W, eps, la, data, mixed_pieces());
      // Closed and sticking pairs only: symmetric (Cholesky).
      NewtonBlocks stick(5);
      for (unsigned int c = 0; c < 5; ++c)
        stick[c].A = (0.5 + 0.2 * c) * Eigen::Matrix3d::Identity();
      check_same_operator(W, eps, la, data, stick);
      // With two floating modes (G columns in the Newton matrix).
      ContactData floating = data;
      floating.G           = Mat::Zero(15, 2);
      for (unsigned int c = 0; c < 5; ++c)
        {
          floating.G(3 * c, 0)     = 1.;
          floating.G(3 * c + 1, 1) = 0.5 + 0.1 * c;
        }
      floating.b = Vec::Zero(2);
      check_same_operator(W, eps, la, floating, stick);
    }
}
