#include <igabde/base/json.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace igabde
{
  namespace base
  {
    Json::Json(const double value)
      : kind(Kind::number)
      , number_value(value)
    {}



    Json::Json(const int value)
      : Json(static_cast<double>(value))
    {}



    Json::Json(const unsigned int value)
      : Json(static_cast<double>(value))
    {}



    Json::Json(const unsigned long value)
      : Json(static_cast<double>(value))
    {}



    Json::Json(const unsigned long long value)
      : Json(static_cast<double>(value))
    {}



    Json::Json(const bool value)
      : kind(Kind::boolean)
      , boolean_value(value)
    {}



    Json::Json(const std::string &value)
      : kind(Kind::string)
      , string_value(value)
    {}



    Json::Json(const char *value)
      : Json(std::string(value))
    {}



    Json
    Json::array()
    {
      Json j;
      j.kind = Kind::array;
      return j;
    }



    Json
    Json::object()
    {
      Json j;
      j.kind = Kind::object;
      return j;
    }



    Json &
    Json::operator[](const std::string &key)
    {
      if (kind == Kind::null)
        kind = Kind::object;
      for (auto &member : members)
        if (member.first == key)
          return member.second;
      members.emplace_back(key, Json());
      return members.back().second;
    }



    void
    Json::push_back(const Json &value)
    {
      if (kind == Kind::null)
        kind = Kind::array;
      elements.push_back(value);
    }



    bool
    Json::has(const std::string &key) const
    {
      for (const auto &member : members)
        if (member.first == key)
          return true;
      return false;
    }



    const Json &
    Json::at(const std::string &key) const
    {
      for (const auto &member : members)
        if (member.first == key)
          return member.second;
      throw std::out_of_range("summary has no member '" + key + "'");
    }



    const Json &
    Json::at(const unsigned int i) const
    {
      if (i >= elements.size())
        throw std::out_of_range("summary array index out of range");
      return elements[i];
    }



    unsigned int
    Json::size() const
    {
      return kind == Kind::array ? elements.size() : members.size();
    }



    double
    Json::number() const
    {
      if (kind != Kind::number)
        throw std::runtime_error("summary value is not a number");
      return number_value;
    }



    const std::string &
    Json::string() const
    {
      if (kind != Kind::string)
        throw std::runtime_error("summary value is not a string");
      return string_value;
    }



    void
    Json::write(std::ostream &out, const unsigned int indent) const
    {
      write(out, indent, 0);
      out << '\n';
    }



    namespace
    {
      std::string
      escape(const std::string &s)
      {
        std::ostringstream o;
        o << '"';
        for (const char c : s)
          switch (c)
            {
              case '"':
                o << "\\\"";
                break;
              case '\\':
                o << "\\\\";
                break;
              case '\n':
                o << "\\n";
                break;
              case '\t':
                o << "\\t";
                break;
              default:
                if (static_cast<unsigned char>(c) < 0x20)
                  o << "\\u" << std::hex << std::setw(4) << std::setfill('0')
                    << static_cast<int>(c) << std::dec;
                else
                  o << c;
            }
        o << '"';
        return o.str();
      }
    } // namespace



    void
    Json::write(std::ostream      &out,
                const unsigned int indent,
                const unsigned int level) const
    {
      const std::string pad(indent * (level + 1), ' ');
      const std::string end_pad(indent * level, ' ');
      switch (kind)
        {
          case Kind::null:
            out << "null";
            break;
          case Kind::boolean:
            out << (boolean_value ? "true" : "false");
            break;
          case Kind::number:
            if (!std::isfinite(number_value))
              out << "null"; // JSON has no NaN/inf
            else if (number_value == std::floor(number_value) &&
                     std::abs(number_value) < 1e15)
              out << static_cast<long long>(number_value);
            else
              out << std::setprecision(17) << number_value; // round-trips
            break;
          case Kind::string:
            out << escape(string_value);
            break;
          case Kind::array:
            if (elements.empty())
              {
                out << "[]";
                break;
              }
            out << "[\n";
            for (unsigned int i = 0; i < elements.size(); ++i)
              {
                out << pad;
                elements[i].write(out, indent, level + 1);
                out << (i + 1 < elements.size() ? ",\n" : "\n");
              }
            out << end_pad << "]";
            break;
          case Kind::object:
            if (members.empty())
              {
                out << "{}";
                break;
              }
            out << "{\n";
            for (unsigned int i = 0; i < members.size(); ++i)
              {
                out << pad << escape(members[i].first) << ": ";
                members[i].second.write(out, indent, level + 1);
                out << (i + 1 < members.size() ? ",\n" : "\n");
              }
            out << end_pad << "}";
            break;
        }
    }
  } // namespace base
} // namespace igabde
