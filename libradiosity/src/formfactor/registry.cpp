// The form-factor methods, by name. Adding a method: one file under src/formfactor/ that
// defines `const FormFactorMethod& NAME_method()`, plus one X(NAME) line here.
#include "core/named_registry.hpp"
#include "radiosity/formfactor_method.hpp"

// clang-format off
#define RAD_FORM_FACTOR_METHODS(X) \
    X(analytic)                    \
    X(pairwise)                    \
    X(hemisphere)                  \
    X(hemicube)                    \
    /* one X(name) line per method, above this line */
// clang-format on

namespace rad {
namespace ff {
#define RAD_DECLARE_METHOD(name) const FormFactorMethod& name##_method();
RAD_FORM_FACTOR_METHODS(RAD_DECLARE_METHOD)
#undef RAD_DECLARE_METHOD
} // namespace ff

std::span<const FormFactorMethod* const> form_factor_methods() {
#define RAD_LIST_METHOD(name) &ff::name##_method(),
    static const FormFactorMethod* const all[] = {RAD_FORM_FACTOR_METHODS(RAD_LIST_METHOD)};
#undef RAD_LIST_METHOD
    return all;
}

std::vector<std::string> form_factor_method_names() {
    return names_of(form_factor_methods());
}

const FormFactorMethod& form_factor_method(std::string_view name) {
    return find_named(form_factor_methods(), name, "form-factor method");
}

} // namespace rad
