#ifndef igabde_base_disjoint_sets_h
#define igabde_base_disjoint_sets_h

#include <numeric>
#include <vector>

namespace igabde
{
  namespace base
  {
    /**
     * @brief Union-find over 0 .. n-1 with path halving. The root of a set
     * is its smallest member: numbering the sets by their roots keeps the
     * order of first appearance, and everything joined to 0 has root 0.
     */
    class DisjointSets
    {
    public:
      explicit DisjointSets(const unsigned int n)
        : parent(n)
      {
        std::iota(parent.begin(), parent.end(), 0u);
      }

      /// The root (smallest member) of @p a's set.
      unsigned int
      find(unsigned int a)
      {
        while (parent[a] != a)
          {
            parent[a] = parent[parent[a]];
            a         = parent[a];
          }
        return a;
      }

      /// Joins the sets of @p a and @p b.
      void
      join(const unsigned int a, const unsigned int b)
      {
        const unsigned int ra = find(a), rb = find(b);
        if (ra < rb)
          parent[rb] = ra;
        else if (rb < ra)
          parent[ra] = rb;
      }

    private:
      std::vector<unsigned int> parent;
    };
  } // namespace base
} // namespace igabde

#endif
