// Tests of the [output] section's picture keys: what they set, and the message of each error.
#include <catch2/catch.hpp>

#include "latfrac/base/error.h"
#include "latfrac/io/problem_file.h"

using Catch::Matchers::Contains;
using latfrac::parse_problem;

namespace {

std::string problem(int dim, const std::string& output) {
  const std::string size = dim == 2 ? "[60e3, 30e3]" : "[60e3, 10e3, 30e3]";
  return "name = \"t\"\n[lattice]\ndim = " + std::to_string(dim) +
         "\nspacing = 2000\nsize = " + size +
         "\n[material]\ndensity = 2600\nyoung = 100e9\npoisson = 0.2\n[output]\n" + output;
}

std::string error_of(const std::string& text) {
  try {
    parse_problem(text, "t.toml", {});
  } catch (const latfrac::InputError& error) {
    return error.what();
  }
  FAIL("no InputError for:\n" << text);
  return "";
}

}  // namespace

TEST_CASE("the picture keys set what the picture shows", "[io]") {
  const latfrac::Output defaults = parse_problem(problem(2, ""), "t.toml", {}).output;
  CHECK(defaults.picture);
  CHECK(defaults.picture_format == "png");
  CHECK(defaults.picture_options.view == latfrac::PictureView::section);
  CHECK(defaults.picture_options.style == latfrac::CrackStyle::cracks);
  CHECK(defaults.picture_options.field == latfrac::NodeField::none);
  CHECK_FALSE(defaults.picture_options.faults);
  CHECK_FALSE(defaults.picture_options.section_at);

  const latfrac::Output output =
      parse_problem(problem(3,
                            "picture_format = \"svg\"\npicture_view = \"section\"\n"
                            "picture_style = \"particles\"\npicture_field = \"von_mises\"\n"
                            "picture_faults = true\npicture_width = 900\nsection_x = 25e3\n"),
                    "t.toml", {})
          .output;
  CHECK(output.picture_format == "svg");
  CHECK(output.picture_options.style == latfrac::CrackStyle::particles);
  CHECK(output.picture_options.field == latfrac::NodeField::von_mises);
  CHECK(output.picture_options.faults);
  CHECK(output.picture_options.width == 900);
  CHECK(output.picture_options.section_axis == latfrac::SectionAxis::x);
  CHECK(output.picture_options.section_at == 25e3);
  CHECK(parse_problem(problem(3, "picture_view = \"oblique\""), "t.toml", {})
            .output.picture_options.view == latfrac::PictureView::oblique);
}

TEST_CASE("bad picture keys name what is allowed", "[io]") {
  CHECK_THAT(error_of(problem(2, "picture_field = \"sigma_x\"")),
             Contains("output.picture_field: \"sigma_x\" is not allowed (did you mean") &&
                 Contains("\"sigma_xx\""));
  CHECK_THAT(error_of(problem(2, "picture_format = \"jpg\"")),
             Contains("output.picture_format: \"jpg\" is not allowed") && Contains("\"svg\""));
  CHECK_THAT(error_of(problem(2, "picture_view = \"map\"")),
             Contains("output.picture_view: \"map\" needs a 3-D block"));
  CHECK_THAT(error_of(problem(2, "section_y = 100")),
             Contains("output.section_y: only applies in 3-D"));
  CHECK_THAT(error_of(problem(3, "section_y = 20e3")),
             Contains("output.section_y: 20000 is out of range; allowed: 0 <= section_y <= 10000"));
  CHECK_THAT(error_of(problem(3, "section_y = 1\nsection_x = 1")),
             Contains("output.section_x: is given with section_y"));
  CHECK_THAT(error_of(problem(2, "picture_width = 50")), Contains("output.picture_width"));
}
