#ifndef igabde_nurbs_knot_vector_h
#define igabde_nurbs_knot_vector_h

#include <deal.II/lac/full_matrix.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace nurbs
  {
    using namespace dealii;

    /**
     * @brief An open (clamped) knot vector with its polynomial degree, and
     * the univariate B-spline machinery on it.
     *
     * The knot vector is stored in full: u_0 <= u_1 <= ... <= u_{m-1}, with
     * the first and last knots repeated p+1 times, so that there are
     * n = m - p - 1 basis functions N_0..N_{n-1}. Knot indices follow Piegl
     * and Tiller, "The NURBS Book" (2nd ed.): the span of u is the index k
     * with u_k <= u < u_{k+1} (the last non-empty span for u = u_{m-1}), and
     * the basis functions that do not vanish there are N_{k-p}..N_k.
     *
     * Non-empty spans (the elements) are numbered 0..n_spans()-1 from left to
     * right.
     */
    class KnotVector
    {
    public:
      /**
       * @brief An empty knot vector (degree 0, no knots); only useful as a
       * placeholder before assignment.
       */
      KnotVector() = default;

      /**
       * @brief Builds and validates the knot vector.
       * @param degree Polynomial degree p >= 1.
       * @param knots Full knot vector (u_0..u_{m-1}).
       *
       * Throws ExcMessage naming the defect and the fix when the knots are
       * decreasing, not open (first/last knot repeated p+1 times), have an
       * interior knot repeated more than p times (a discontinuous basis) or
       * are too few (fewer than 2(p+1)).
       */
      KnotVector(const unsigned int degree, const std::vector<double> &knots);

      /**
       * @brief The open knot vector of degree @p degree with @p n_spans equal
       * spans on [@p a, @p b] and single interior knots (maximal continuity
       * C^{p-1}).
       */
      static KnotVector
      uniform(const unsigned int degree,
              const unsigned int n_spans,
              const double       a = 0.,
              const double       b = 1.);

      /// @brief Polynomial degree p.
      unsigned int
      degree() const;

      /// @brief The full knot vector.
      const std::vector<double> &
      knots() const;

      /// @brief Number of basis functions n = m - p - 1.
      unsigned int
      n_basis_functions() const;

      /// @brief First knot (start of the parametric interval).
      double
      front() const;

      /// @brief Last knot (end of the parametric interval).
      double
      back() const;

      /**
       * @brief Knot span index k with u_k <= u < u_{k+1} (P&T A2.1); u is
       * clamped to [front(), back()] and u = back() gives the last non-empty
       * span.
       */
      unsigned int
      find_span(const double u) const;

      /// @brief The distinct knot values (breakpoints), increasing.
      std::vector<double>
      breakpoints() const;

      /// @brief Multiplicity of each breakpoint, in the order of
      /// breakpoints().
      std::vector<unsigned int>
      multiplicities() const;

      /// @brief Number of non-empty knot spans (elements).
      unsigned int
      n_spans() const;

      /**
       * @brief Knot index k (u_k < u_{k+1}) of the non-empty span @p e; the
       * nonzero functions on it are N_{k-p}..N_k.
       */
      unsigned int
      span_knot_index(const unsigned int e) const;

      /**
       * @brief Index of the non-empty span (element) containing @p u, 0-based
       * among non-empty spans; u = back() is in the last one.
       */
      unsigned int
      element_of(const double u) const;

      /**
       * @brief Greville abscissae g_i = (u_{i+1} + ... + u_{i+p}) / p, one
       * per basis function; they lie in [front(), back()] and are the
       * classical collocation points (Schoenberg-Whitney holds).
       */
      std::vector<double>
      greville_abscissae() const;

      /**
       * @brief The p+1 nonzero basis functions N_{k-p}..N_k at @p u in span
       * @p span (P&T A2.2, Cox-de Boor).
       */
      void
      basis_functions(const double         u,
                      const unsigned int   span,
                      std::vector<double> &values) const;

      /**
       * @brief The nonzero basis functions and their derivatives up to order
       * @p n_derivatives at @p u (P&T A2.3): @p ders[k][j] is the k-th
       * derivative of N_{span-p+j}.
       */
      void
      basis_function_derivatives(const double       u,
                                 const unsigned int span,
                                 const unsigned int n_derivatives,
                                 std::vector<std::vector<double>> &ders) const;

      /// The largest degree basis_and_first_derivatives() takes.
      static constexpr unsigned int max_fast_degree = 10;

      /**
       * @brief basis_function_derivatives() with one derivative, without
       * allocating (the same operations, so the same numbers): @p values
       * and @p derivatives get the p+1 entries; degree at most
       * max_fast_degree.
       */
      void
      basis_and_first_derivatives(const double       u,
                                  const unsigned int span,
                                  double            *values,
                                  double            *derivatives) const;

      /**
       * @brief The Bézier extraction operator of every non-empty span (Borden,
       * Scott, Evans, Hughes, IJNME 87 (2011) 15-47, Algorithm 1).
       *
       * For span e with knot index k and local coordinate t in [0, 1],
       * N_{k-p+a}(u) = sum_b C^e(a, b) B_b(t), where B_b(t) = binom(p, b)
       * t^b (1-t)^(p-b) are the Bernstein polynomials on [0, 1]. Each matrix
       * is (p+1) x (p+1).
       */
      std::vector<FullMatrix<double>>
      bezier_extraction_operators() const;

      /**
       * @brief The knot vector with @p t added to the degree (every distinct
       * knot's multiplicity rises by t, so the continuity is kept).
       */
      KnotVector
      elevated(const unsigned int t) const;

      /// @brief Equality of degree and knots (exact comparison).
      bool
      operator==(const KnotVector &other) const;

    private:
      unsigned int        p = 0;
      std::vector<double> u;
    };
  } // namespace nurbs
} // namespace igabde

#endif
