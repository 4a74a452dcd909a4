// The names of the picture options, as problem files and the command line spell them.
#include "latfrac/scene/picture_options.h"

#include <cstddef>

namespace latfrac {
namespace {

template <class Enum>
std::optional<Enum> named(const std::vector<std::string_view>& names, std::string_view name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<Enum>(i);
  return std::nullopt;
}

}  // namespace

const std::vector<std::string_view>& picture_view_names() {
  static const std::vector<std::string_view> names{"section", "map", "oblique"};
  return names;
}

const std::vector<std::string_view>& crack_style_names() {
  static const std::vector<std::string_view> names{"cracks", "particles"};
  return names;
}

const std::vector<std::string_view>& node_field_names() {
  static const std::vector<std::string_view> names{
      "none",     "displacement", "ux",       "uy",         "uz",        "sigma_xx", "sigma_yy",
      "sigma_zz", "sigma_xz",     "sigma_mean", "von_mises", "sqrt_j2",   "f"};
  return names;
}

const std::vector<std::string_view>& picture_format_names() {
  static const std::vector<std::string_view> names{"png", "svg", "pdf"};
  return names;
}

std::string_view name_of(PictureView view) {
  return picture_view_names()[static_cast<std::size_t>(view)];
}
std::string_view name_of(CrackStyle style) {
  return crack_style_names()[static_cast<std::size_t>(style)];
}
std::string_view name_of(NodeField field) {
  return node_field_names()[static_cast<std::size_t>(field)];
}

std::optional<PictureView> picture_view_named(std::string_view name) {
  return named<PictureView>(picture_view_names(), name);
}
std::optional<CrackStyle> crack_style_named(std::string_view name) {
  return named<CrackStyle>(crack_style_names(), name);
}
std::optional<NodeField> node_field_named(std::string_view name) {
  return named<NodeField>(node_field_names(), name);
}

std::string list_of_names(const std::vector<std::string_view>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text.append(names[i]);
  }
  return text;
}

}  // namespace latfrac
