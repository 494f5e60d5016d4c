#ifndef igabde_base_json_h
#define igabde_base_json_h

#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace base
  {
    /**
     * @brief A minimal ordered JSON value for summary.json: null, bool,
     * number, string, array or object (keys keep insertion order).
     */
    class Json
    {
    public:
      /// null
      Json() = default;
      /// number
      Json(const double value);
      /// number (integer)
      Json(const int value);
      /// number (unsigned)
      Json(const unsigned int value);
      /// number (count)
      Json(const unsigned long value);
      /// number (count)
      Json(const unsigned long long value);
      /// bool
      Json(const bool value);
      /// string
      Json(const std::string &value);
      /// string
      Json(const char *value);

      /// An empty array.
      static Json
      array();

      /// An empty object.
      static Json
      object();

      /// Object member access; makes this an object and adds @p key if new.
      Json &
      operator[](const std::string &key);

      /// Appends to an array (makes this an array if null).
      void
      push_back(const Json &value);

      /// Whether this object has the member @p key.
      bool
      has(const std::string &key) const;

      /// Object member @p key; throws if there is none.
      const Json &
      at(const std::string &key) const;

      /// Array element @p i; throws if out of range.
      const Json &
      at(const unsigned int i) const;

      /// Number of array elements or object members.
      unsigned int
      size() const;

      /// The number; throws if this is not a number.
      double
      number() const;

      /// The string; throws if this is not a string.
      const std::string &
      string() const;

      /// Writes the value, indented by @p indent spaces per level.
      void
      write(std::ostream &out, const unsigned int indent = 2) const;

    private:
      enum class Kind
      {
        null,
        boolean,
        number,
        string,
        array,
        object
      };

      void
      write(std::ostream      &out,
            const unsigned int indent,
            const unsigned int level) const;

      Kind                                      kind          = Kind::null;
      bool                                      boolean_value = false;
      double                                    number_value  = 0.;
      std::string                               string_value;
      std::vector<Json>                         elements;
      std::vector<std::pair<std::string, Json>> members;
    };
  } // namespace base
} // namespace igabde

#endif
