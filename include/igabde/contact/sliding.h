#ifndef igabde_contact_sliding_h
#define igabde_contact_sliding_h

#include <igabde/base/choice_names.h>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief Contact/Sliding: whether the pairs are formed once on the
     * reference configuration (small) or again on the current one at every
     * load step and Newton iterate (finite; FiniteSliding).
     */
    enum class Sliding
    {
      small,
      finite
    };

    /** @brief The names of Sliding as the scene writes them. */
    inline constexpr base::ChoiceNames<Sliding, 2> sliding_names = {
      {{Sliding::small, "small"}, {Sliding::finite, "finite"}}};

    /**
     * @brief Contact/Sliding tangent: with finite sliding, whether the
     * Newton matrix holds the pairs' operators at the iterate (frozen),
     * also their derivatives by the configuration (full;
     * FiniteSliding::tangent), or the frozen one until the residual
     * contracts slowly and the full one from there to the end of the
     * Newton phase (adaptive, "auto"), or the full one with every
     * derivative by finite differences of the pairing (differences; full
     * takes them in closed form where the pairing has them).
     */
    enum class SlidingTangent
    {
      frozen,
      full,
      adaptive,
      differences
    };

    /** @brief The names of SlidingTangent as the scene writes them. */
    inline constexpr base::ChoiceNames<SlidingTangent, 4>
      sliding_tangent_names = {{{SlidingTangent::frozen, "frozen"},
                                {SlidingTangent::full, "full"},
                                {SlidingTangent::adaptive, "auto"},
                                {SlidingTangent::differences, "differences"}}};
  } // namespace contact
} // namespace igabde

#endif
