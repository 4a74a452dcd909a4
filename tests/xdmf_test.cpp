// Tests of the XDMF description: well-formed XML whose every HDF reference resolves in the .h5.
#include "latfrac/io/xdmf.h"

#include <hdf5.h>

#include <catch2/catch.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "latfrac/base/error.h"
#include "latfrac/io/result_file.h"
#include "sample_result.h"

namespace latfrac {
namespace {

using testing::sample_result;
using testing::ScratchDirectory;

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<XmlElement> children;
};

// Just enough XML for the check: a prolog, comments, elements, attributes, text and the five
// predefined entities. Throws std::runtime_error on anything malformed, unbalanced tags first.
class XmlParser final {
 public:
  explicit XmlParser(std::string text) : text_(std::move(text)) {}

  XmlElement document() {
    skip_prolog_and_comments();
    XmlElement root = element();
    skip_prolog_and_comments();
    if (position_ != text_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(what + " at offset " + std::to_string(position_));
  }

  bool consume(const std::string& token) {
    if (text_.compare(position_, token.size(), token) != 0) return false;
    position_ += token.size();
    return true;
  }

  void expect(const std::string& token) {
    if (!consume(token)) fail("expected '" + token + "'");
  }

  void skip_space() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) {
      ++position_;
    }
  }

  void skip_until(const std::string& token) {
    const std::size_t end = text_.find(token, position_);
    if (end == std::string::npos) fail("missing '" + token + "'");
    position_ = end + token.size();
  }

  void skip_prolog_and_comments() {
    for (skip_space();; skip_space()) {
      if (consume("<?")) {
        skip_until("?>");
      } else if (consume("<!--")) {
        skip_until("-->");
      } else {
        return;
      }
    }
  }

  std::string name() {
    const std::size_t start = position_;
    while (position_ < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[position_])) ||
            std::string_view("_:-.").find(text_[position_]) != std::string_view::npos)) {
      ++position_;
    }
    if (position_ == start) fail("expected a name");
    return text_.substr(start, position_ - start);
  }

  std::string unescape(const std::string& raw) const {
    static const std::map<std::string, char> entities{
        {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
    std::string text;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '<') fail("raw '<' in a value");
      if (raw[i] != '&') {
        text += raw[i];
        continue;
      }
      const std::size_t end = raw.find(';', i);
      const auto entity =
          end == std::string::npos ? entities.end() : entities.find(raw.substr(i + 1, end - i - 1));
      if (entity == entities.end()) fail("unknown entity in '" + raw + "'");
      text += entity->second;
      i = end;
    }
    return text;
  }

  XmlElement element() {
    expect("<");
    XmlElement element;
    element.name = name();
    for (skip_space(); !consume(">"); skip_space()) {
      if (consume("/>")) return element;
      const std::string key = name();
      expect("=\"");
      const std::size_t end = text_.find('"', position_);
      if (end == std::string::npos) fail("unterminated attribute value");
      if (!element.attributes.emplace(key, unescape(text_.substr(position_, end - position_)))
               .second) {
        fail("attribute " + key + " given twice");
      }
      position_ = end + 1;
    }
    while (true) {
      const std::size_t next_tag = text_.find('<', position_);
      if (next_tag == std::string::npos) fail("<" + element.name + "> is never closed");
      element.text += unescape(text_.substr(position_, next_tag - position_));
      position_ = next_tag;
      if (consume("</")) {
        if (name() != element.name) fail("<" + element.name + "> closed by another tag");
        skip_space();
        expect(">");
        return element;
      }
      if (consume("<!--")) {
        skip_until("-->");
      } else {
        element.children.push_back(this->element());
      }
    }
  }

  std::string text_;
  std::size_t position_ = 0;
};

void visit(const XmlElement& element, const std::function<void(const XmlElement&)>& action) {
  action(element);
  for (const XmlElement& child : element.children) visit(child, action);
}

std::vector<const XmlElement*> find_all(const XmlElement& root, const std::string& name) {
  std::vector<const XmlElement*> found;
  visit(root, [&](const XmlElement& element) {
    if (element.name == name) found.push_back(&element);
  });
  return found;
}

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::vector<hsize_t> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<hsize_t> values;
  for (hsize_t value; in >> value;) values.push_back(value);
  return values;
}

// The shape, element size and number type of the dataset a Format="HDF" DataItem names must
// be those of the dataset in the .h5.
void require_resolves(const XmlElement& item, const std::string& h5_path,
                      const std::string& h5_name) {
  const std::string reference = trimmed(item.text);
  INFO("DataItem " << reference);
  const std::size_t colon = reference.find(':');
  REQUIRE(colon != std::string::npos);
  CHECK(reference.substr(0, colon) == h5_name);
  const std::string dataset_path = reference.substr(colon + 1);

  const hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const hid_t dataset = H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT);
  REQUIRE(dataset >= 0);
  const hid_t space = H5Dget_space(dataset);
  std::vector<hsize_t> shape(H5Sget_simple_extent_ndims(space));
  H5Sget_simple_extent_dims(space, shape.data(), nullptr);
  const hid_t type = H5Dget_type(dataset);
  const H5T_class_t type_class = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  const bool is_signed = type_class == H5T_INTEGER && H5Tget_sign(type) == H5T_SGN_2;
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(dataset);
  H5Fclose(file);

  CHECK(numbers(item.attributes.at("Dimensions")) == shape);
  CHECK(std::stoul(item.attributes.at("Precision")) == size);
  const std::string& number_type = item.attributes.at("NumberType");
  if (number_type == "Float") {
    CHECK(type_class == H5T_FLOAT);
  } else if (number_type == "Int" || number_type == "Char") {
    CHECK(is_signed);
  } else {
    CHECK(number_type == "UChar");
    CHECK(type_class == H5T_INTEGER);
    CHECK_FALSE(is_signed);
  }
}

// Writes result's .h5 and .xmf side by side, checks the .xmf against the .h5, returns its root.
XmlElement write_and_check(const RunResult& result, const ScratchDirectory& scratch) {
  const std::string h5_path = scratch.file("graben.h5");
  const std::string xmf_path = scratch.file("graben.xmf");
  write_result_file(h5_path, result);
  write_xdmf(xmf_path, "graben.h5", result);
  CHECK_FALSE(std::filesystem::exists(xmf_path + ".partial"));

  std::ifstream in(xmf_path);
  std::stringstream text;
  text << in.rdbuf();
  XmlElement root;
  REQUIRE_NOTHROW(root = XmlParser(text.str()).document());
  REQUIRE(root.name == "Xdmf");
  REQUIRE(find_all(root, "Domain").size() == 1);

  const auto items = find_all(root, "DataItem");
  REQUIRE(!items.empty());
  for (const XmlElement* item : items) {
    REQUIRE(item->attributes.at("Format") == "HDF");
    require_resolves(*item, h5_path, "graben.h5");
  }
  for (const XmlElement* topology : find_all(root, "Topology")) {
    REQUIRE(topology->children.size() == 1);
    const auto dimensions = numbers(topology->children[0].attributes.at("Dimensions"));
    CHECK(numbers(topology->attributes.at("NumberOfElements")).at(0) == dimensions.at(0));
  }
  return root;
}

}  // namespace

TEST_CASE("the XML checker of these tests rejects malformed XML", "[io]") {
  CHECK_NOTHROW(XmlParser("<?xml version=\"1.0\"?><a x=\"&lt;\"><b/>t</a>").document());
  CHECK_THROWS(XmlParser("<a><b></a>").document());
  CHECK_THROWS(XmlParser("<a><b/>").document());
  CHECK_THROWS(XmlParser("<a x=\"&\"/>").document());
  CHECK_THROWS(XmlParser("<a/><b/>").document());
}

TEST_CASE("the XDMF file describes one time step per snapshot", "[io]") {
  ScratchDirectory scratch;
  RunResult result = sample_result();
  result.scene.name = "graben \"A\" & <B>";
  const XmlElement root = write_and_check(result, scratch);

  const XmlElement& temporal = root.children.at(0).children.at(0);
  CHECK(temporal.attributes.at("CollectionType") == "Temporal");
  CHECK(temporal.attributes.at("Name") == result.scene.name);
  REQUIRE(temporal.children.size() == result.snapshots.size());
  for (std::size_t i = 0; i < result.snapshots.size(); ++i) {
    const XmlElement& step = temporal.children[i];
    CHECK(step.attributes.at("CollectionType") == "Spatial");
    REQUIRE(step.children.size() == 3);
    CHECK(step.children[0].name == "Time");
    CHECK(std::stod(step.children[0].attributes.at("Value")) == result.snapshots[i].lambda);
    CHECK(step.children[1].attributes.at("Name") == "nodes");
    CHECK(step.children[2].attributes.at("Name") == "bonds");
  }
  CHECK(find_all(root, "Attribute").size() == 6 * result.snapshots.size());
}

TEST_CASE("the XDMF file of a run without snapshots shows the lattice without time", "[io]") {
  ScratchDirectory scratch;
  RunResult result = sample_result();
  result.snapshots.clear();
  result.events.clear();
  const XmlElement root = write_and_check(result, scratch);

  CHECK(find_all(root, "Time").empty());
  const XmlElement& lattice = root.children.at(0).children.at(0);
  CHECK(lattice.attributes.at("CollectionType") == "Spatial");
  CHECK(find_all(root, "Grid").size() == 3);
  CHECK(find_all(root, "Attribute").size() == 1);
}

TEST_CASE("an XDMF file that cannot be written throws and leaves nothing", "[io]") {
  ScratchDirectory scratch;
  const std::string path = scratch.file("missing/graben.xmf");
  CHECK_THROWS_AS(write_xdmf(path, "graben.h5", sample_result()), Error);
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(std::filesystem::exists(path + ".partial"));
}

}  // namespace latfrac
