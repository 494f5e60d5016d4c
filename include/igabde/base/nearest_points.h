#ifndef igabde_base_nearest_points_h
#define igabde_base_nearest_points_h

#include <deal.II/base/point.h>

#include <deal.II/numerics/rtree.h>

#include <boost/geometry/index/rtree.hpp>
#include <iterator>
#include <utility>
#include <vector>

namespace igabde
{
  namespace base
  {
    using namespace dealii;

    /**
     * @brief Sample points with an R-tree over them (deal.II's
     * pack_rtree_of_indices(), Boost.Geometry): the start of every
     * closest-point search (a contact surface's samples, a patch's samples
     * for the inversion of its map), in O(log n) per query instead of a
     * scan.
     */
    template <int dim>
    class NearestPoints
    {
    public:
      explicit NearestPoints(std::vector<Point<dim>> samples)
        : samples(std::move(samples))
        , tree(pack_rtree_of_indices(this->samples))
      {}

      // The tree refers to the samples it was packed from.
      NearestPoints(const NearestPoints &) = delete;
      NearestPoints &
      operator=(const NearestPoints &) = delete;

      /** @brief Whether there are no samples. */
      bool
      empty() const
      {
        return samples.empty();
      }

      /**
       * @brief The index of the sample nearest to @p x; of several at the
       * same distance, the first (as a scan in index order would find).
       */
      unsigned int
      nearest(const Point<dim> &x) const
      {
        std::vector<std::size_t> candidates;
        tree.query(boost::geometry::index::nearest(x, 8),
                   std::back_inserter(candidates));
        std::size_t best = candidates.front();
        for (const std::size_t c : candidates)
          {
            const double dc = samples[c].distance_square(x);
            const double db = samples[best].distance_square(x);
            if (dc < db || (dc == db && c < best))
              best = c;
          }
        return best;
      }

      /**
       * @brief The distance from sample @p i to the nearest other sample
       * (0 if there is none).
       */
      double
      spacing(const unsigned int i) const
      {
        std::vector<std::size_t> candidates;
        tree.query(boost::geometry::index::nearest(samples[i], 2),
                   std::back_inserter(candidates));
        double result = 0.;
        for (const std::size_t c : candidates)
          if (c != i)
            result = samples[c].distance(samples[i]);
        return result;
      }

      /** @brief Sample @p i. */
      const Point<dim> &
      operator[](const unsigned int i) const
      {
        return samples[i];
      }

    private:
      const std::vector<Point<dim>>                       samples;
      const decltype(pack_rtree_of_indices(
        std::declval<const std::vector<Point<dim>> &>())) tree;
    };
  } // namespace base
} // namespace igabde

#endif
