// Unit tests of the univariate B-spline kernels: knot-vector validation,
// Cox-de Boor values and derivatives, Bézier extraction.
#include <igabde/nurbs/knot_vector.h>

#include <deal.II/base/polynomials_bernstein.h>

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <random>
#include <string>

using igabde::nurbs::KnotVector;

namespace
{
  // Expects the construction to throw with a message containing @p text.
  void
  expect_invalid(const unsigned int         p,
                 const std::vector<double> &u,
                 const std::string         &text)
  {
    try
      {
        KnotVector kv(p, u);
        FAIL() << "no exception for a knot vector that should be invalid ("
               << text << ")";
      }
    catch (const std::exception &e)
      {
        // deal.II wraps long messages: compare with whitespace collapsed.
        std::string message;
        for (const char c : std::string(e.what()))
          if (!std::isspace(static_cast<unsigned char>(c)))
            message += c;
          else if (!message.empty() && message.back() != ' ')
            message += ' ';
        EXPECT_NE(message.find(text), std::string::npos)
          << "message was: " << e.what();
      }
  }

  std::vector<KnotVector>
  sample_knot_vectors()
  {
    return {KnotVector(1, {0, 0, 1, 1}),
            KnotVector(2, {0, 0, 0, 1, 1, 1}),
            KnotVector(2, {0, 0, 0, 0.5, 1, 1, 1}),
            KnotVector(2, {0, 0, 0, 0.3, 0.3, 0.7, 1, 1, 1}),
            KnotVector(3, {0, 0, 0, 0, 0.25, 0.5, 0.5, 0.75, 1, 1, 1, 1}),
            KnotVector(3, {-1, -1, -1, -1, 0.2, 0.2, 0.2, 2, 2, 2, 2}),
            KnotVector(4, {0, 0, 0, 0, 0, 0.1, 0.4, 0.4, 1, 1, 1, 1, 1}),
            KnotVector::uniform(2, 5, 0., 3.)};
  }
} // namespace



TEST(NurbsKnotVector, ValidationErrors)
{
  expect_invalid(2, {0, 0, 0, 0.6, 0.5, 1, 1, 1}, "non-decreasing");
  expect_invalid(2, {0, 0, 0.5, 1, 1, 1}, "not open");
  expect_invalid(2, {0, 0, 0, 0.5, 1, 1}, "not open");
  expect_invalid(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, "repeated 3 times");
  expect_invalid(2, {0, 0, 1, 1}, "too few knots");
  expect_invalid(2, {0, 0, 0, 0, 1, 1, 1}, "more than p+1");
  expect_invalid(0, {0, 1}, "at least 1");
  expect_invalid(1, {1, 1, 1, 1}, "positive length");
  EXPECT_NO_THROW(KnotVector(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}));
}



TEST(NurbsKnotVector, SpansBreakpointsGreville)
{
  const KnotVector kv(2, {0, 0, 0, 0.3, 0.3, 0.7, 1, 1, 1});
  EXPECT_EQ(kv.n_basis_functions(), 6u);
  EXPECT_EQ(kv.n_spans(), 3u);
  EXPECT_EQ(kv.breakpoints(), (std::vector<double>{0, 0.3, 0.7, 1}));
  EXPECT_EQ(kv.multiplicities(), (std::vector<unsigned int>{3, 2, 1, 3}));
  EXPECT_EQ(kv.find_span(0.), 2u);
  EXPECT_EQ(kv.find_span(0.3), 4u);
  EXPECT_EQ(kv.find_span(0.5), 4u);
  EXPECT_EQ(kv.find_span(1.), 5u);
  EXPECT_EQ(kv.span_knot_index(0), 2u);
  EXPECT_EQ(kv.span_knot_index(1), 4u);
  EXPECT_EQ(kv.span_knot_index(2), 5u);
  EXPECT_EQ(kv.element_of(0.1), 0u);
  EXPECT_EQ(kv.element_of(0.3), 1u);
  EXPECT_EQ(kv.element_of(1.0), 2u);
  const auto                g        = kv.greville_abscissae();
  const std::vector<double> expected = {0, 0.15, 0.3, 0.5, 0.85, 1};
  ASSERT_EQ(g.size(), expected.size());
  for (unsigned int i = 0; i < g.size(); ++i)
    EXPECT_NEAR(g[i], expected[i], 1e-15);

  const KnotVector e = kv.elevated(1);
  EXPECT_EQ(e.degree(), 3u);
  EXPECT_EQ(e.multiplicities(), (std::vector<unsigned int>{4, 3, 2, 4}));
}



TEST(NurbsKnotVector, PartitionOfUnityAndDerivatives)
{
  std::mt19937                           rng(42);
  std::uniform_real_distribution<double> unit(0., 1.);
  for (const auto &kv : sample_knot_vectors())
    {
      const unsigned int p = kv.degree();
      for (unsigned int s = 0; s < 200; ++s)
        {
          const double x = kv.front() + (kv.back() - kv.front()) * unit(rng);
          const unsigned int k = kv.find_span(x);
          ASSERT_LE(kv.knots()[k], x);
          ASSERT_LT(x, kv.knots()[k + 1]);

          std::vector<double> N;
          kv.basis_functions(x, k, N);
          double sum = 0.;
          for (const double v : N)
            {
              EXPECT_GE(v, -1e-15);
              sum += v;
            }
          EXPECT_NEAR(sum, 1., 1e-14);

          std::vector<std::vector<double>> ders;
          kv.basis_function_derivatives(x, k, 2, ders);
          double dsum = 0.;
          for (unsigned int j = 0; j <= p; ++j)
            {
              EXPECT_NEAR(ders[0][j], N[j], 1e-14);
              dsum += ders[1][j];
            }
          EXPECT_NEAR(dsum, 0., 1e-11);

          // Central differences inside the span (the basis is polynomial
          // there, so the difference quotient is accurate).
          const double h = 1e-6 * (kv.knots()[k + 1] - kv.knots()[k]);
          if (x - h > kv.knots()[k] && x + h < kv.knots()[k + 1])
            {
              std::vector<double> Np, Nm;
              kv.basis_functions(x + h, k, Np);
              kv.basis_functions(x - h, k, Nm);
              for (unsigned int j = 0; j <= p; ++j)
                EXPECT_NEAR(ders[1][j],
                            (Np[j] - Nm[j]) / (2. * h),
                            1e-6 * (1. + std::abs(ders[1][j])));
              if (p >= 2)
                {
                  std::vector<std::vector<double>> dp, dm;
                  kv.basis_function_derivatives(x + h, k, 1, dp);
                  kv.basis_function_derivatives(x - h, k, 1, dm);
                  for (unsigned int j = 0; j <= p; ++j)
                    EXPECT_NEAR(ders[2][j],
                                (dp[1][j] - dm[1][j]) / (2. * h),
                                1e-5 * (1. + std::abs(ders[2][j])));
                }
            }
        }
    }
}



TEST(NurbsKnotVector, BezierExtractionReproducesBSplines)
{
  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> unit(0., 1.);
  for (const auto &kv : sample_knot_vectors())
    {
      const unsigned int p = kv.degree();
      const auto         C = kv.bezier_extraction_operators();
      ASSERT_EQ(C.size(), kv.n_spans());
      const auto bernstein =
        dealii::generate_complete_bernstein_basis<double>(p);
      const auto b = kv.breakpoints();
      for (unsigned int e = 0; e < kv.n_spans(); ++e)
        {
          const unsigned int k = kv.span_knot_index(e);
          for (unsigned int s = 0; s < 20; ++s)
            {
              const double        t = unit(rng);
              const double        x = b[e] + t * (b[e + 1] - b[e]);
              std::vector<double> N;
              kv.basis_functions(x, k, N);
              for (unsigned int a = 0; a <= p; ++a)
                {
                  double v = 0.;
                  for (unsigned int j = 0; j <= p; ++j)
                    v += C[e](a, j) * bernstein[j].value(t);
                  EXPECT_NEAR(v, N[a], 1e-13)
                    << "span " << e << " function " << a << " degree " << p;
                }
            }
        }
    }
}
