// Private: a settings table bound to a C++ struct. Each entry is a Field plus how to read and
// write it in the struct, so a setting is declared by one entry; its default is read from the
// struct's own initialiser (the one place defaults live).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "frictal/settings.hpp"

namespace frictal::settings_detail {

/// Whether a field's lower bound is itself valid (Closed) or not (Open).
enum class Lo { Closed, Open };

/// A field of a settings table: name, SI unit ("" unitless), valid range [min or (min, max] or
/// max) (max_open), one help line and, when the default comes from elsewhere, its text.
inline Field field(std::string name, std::string unit, double min, Lo lo, double max, std::string help,
                   bool max_open = false, std::string text_default = "") {
  Field f;
  f.name = std::move(name);
  f.unit = std::move(unit);
  f.min = min;
  f.min_open = lo == Lo::Open;
  f.max = max;
  f.max_open = max_open;
  f.help = std::move(help);
  f.text_default = std::move(text_default);
  return f;
}
/// The short form that the table files use.
template <class... A>
Field F(A&&... a) {
  return field(std::forward<A>(a)...);
}

/// A quantity that several tables share (settings.hpp, shared_field), by its name.
inline Field shared(const std::string& name) {
  const Field* f = shared_field(name);
  return f ? *f : field(name, "", 0, Lo::Closed, 0, name);  // not reached: every caller names a shared field
}

template <class T>
struct Binding {
  Field field;
  std::function<FieldValue(const T&)> get;
  std::function<void(T&, const FieldValue&)> set;
};

/// A number (double), an integer (int, size_t, uint64) or a bool member reached by `ref(T&)`.
template <class T, class Ref>
Binding<T> bind(Field f, Ref ref) {
  using M = std::remove_reference_t<decltype(ref(std::declval<T&>()))>;
  Binding<T> b;
  if constexpr (std::is_same_v<M, bool>) {
    f.type = FieldType::Boolean;
    b.get = [ref](const T& t) { return FieldValue{ref(const_cast<T&>(t))}; };
    b.set = [ref](T& t, const FieldValue& v) { ref(t) = std::get<bool>(v); };
  } else if constexpr (std::is_integral_v<M>) {
    f.type = FieldType::Integer;
    b.get = [ref](const T& t) { return FieldValue{static_cast<std::int64_t>(ref(const_cast<T&>(t)))}; };
    b.set = [ref](T& t, const FieldValue& v) { ref(t) = static_cast<M>(std::get<std::int64_t>(v)); };
  } else {
    f.type = FieldType::Real;
    b.get = [ref](const T& t) { return FieldValue{static_cast<double>(ref(const_cast<T&>(t)))}; };
    b.set = [ref](T& t, const FieldValue& v) { ref(t) = std::get<double>(v); };
  }
  b.field = std::move(f);
  return b;
}

/// An enum member shown as one of `words` (in the order of `values`).
template <class T, class Ref, class E>
Binding<T> bind_choice(Field f, Ref ref, std::vector<std::pair<std::string, E>> words) {
  f.type = FieldType::Choice;
  for (const auto& [w, e] : words) f.choices.push_back(w);
  Binding<T> b;
  b.get = [ref, words](const T& t) {
    for (const auto& [w, e] : words)
      if (ref(const_cast<T&>(t)) == e) return FieldValue{w};
    return FieldValue{words.front().first};
  };
  b.set = [ref, words](T& t, const FieldValue& v) {
    for (const auto& [w, e] : words)
      if (std::get<std::string>(v) == w) ref(t) = e;
  };
  b.field = std::move(f);
  return b;
}

/// Fills each field's default from a default-constructed struct.
template <class T>
std::vector<Binding<T>> with_defaults(std::vector<Binding<T>> table, const T& defaults) {
  for (auto& b : table) {
    const FieldValue v = b.get(defaults);
    if (b.field.type == FieldType::Choice) {
      const auto& c = b.field.choices;
      // A word that is no choice (an unset optional: "") is "automatic".
      const auto i = std::find(c.begin(), c.end(), std::get<std::string>(v));
      b.field.default_value = i == c.end() ? std::nan("") : static_cast<double>(i - c.begin());
    } else {
      b.field.default_value = as_real(v);
    }
  }
  return table;
}

template <class T>
std::vector<Field> fields_of(const std::vector<Binding<T>>& table) {
  std::vector<Field> f;
  for (const auto& b : table) f.push_back(b.field);
  return f;
}

/// `base` with every value of `si` applied after checking it; names not in the table are an
/// error naming the nearest one. `what` prefixes messages (e.g. "koch").
template <class T>
Result<T> apply(const std::vector<Binding<T>>& table, T base, const ValueSet& si, const std::string& what) {
  for (const auto& [name, value] : si) {
    const Binding<T>* b = nullptr;
    for (const auto& e : table)
      if (e.field.name == name) b = &e;
    if (!b) {
      std::vector<std::string> names;
      for (const auto& e : table) names.push_back(e.field.name);
      std::string hint;
      if (std::string n = nearest_word(name, names); !n.empty()) hint = fmt::format(" (did you mean '{}'?)", n);
      return make_error(fmt::format("{}: unknown parameter '{}'{}", what, name, hint));
    }
    auto checked = check_si_value(b->field, value);
    if (!checked) return with_prefix(what + ": ", checked.error());
    b->set(base, *checked);
  }
  return base;
}

/// Every field's value in `t` (SI).
template <class T>
ValueSet values_of(const std::vector<Binding<T>>& table, const T& t) {
  ValueSet v;
  for (const auto& b : table) v[b.field.name] = b.get(t);
  return v;
}

}  // namespace frictal::settings_detail
