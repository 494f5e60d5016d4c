#ifndef igabde_base_memory_record_h
#define igabde_base_memory_record_h

#include <cstddef>
#include <string>
#include <vector>

namespace igabde
{
  namespace base
  {
    /**
     * @brief Bytes one rank holds for one kind of data, and whether the ranks
     * divide it.
     *
     * Replicated data are held whole by every rank (the same bytes on one
     * rank as on N); divided data are this rank's share of something the
     * ranks hold between them (a share of a distributed matrix or factor,
     * or a body that only its own group of ranks factorises).
     */
    struct MemoryItem
    {
      /// What the bytes are, e.g. "Body 1: sparsity pattern".
      std::string name;
      /// Bytes on this rank.
      double bytes = 0.;
      /// Whether the ranks divide it (false: every rank holds it whole).
      bool divided = false;
    };

    /// The capacity in bytes of a std::vector (its heap allocation).
    template <typename T>
    inline double
    vector_bytes(const std::vector<T> &v)
    {
      return double(v.capacity()) * sizeof(T);
    }
  } // namespace base
} // namespace igabde

#endif
