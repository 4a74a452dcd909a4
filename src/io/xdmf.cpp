// The XDMF (.xmf) description that lets ParaView open a result file.
#include "latfrac/io/xdmf.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <optional>

#include "latfrac/base/atomic_write.h"
#include "latfrac/base/error.h"

namespace latfrac {

namespace {

std::string xml_escape(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string attr(const char* name, const std::string& value) {
  return std::string(" ") + name + "=\"" + xml_escape(value) + "\"";
}

// Shortest text that reads back as the same double.
std::string number_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// One dataset of the .h5 as XDMF sees it.
struct Dataset {
  std::string path;
  std::string dimensions;  // "N 3": the dataset's shape, slowest index first
  const char* number_type;
  int precision;  // bytes
};

Dataset float64(const std::string& path, const std::string& dimensions) {
  return {path, dimensions, "Float", 8};
}

// Lines of XML, indented by nesting depth.
class XmlLines final {
 public:
  void line(const std::string& text) { text_ += std::string(2 * depth_, ' ') + text + '\n'; }
  void open(const std::string& name, const std::string& attributes = "") {
    line("<" + name + attributes + ">");
    ++depth_;
  }
  void close(const std::string& name) {
    --depth_;
    line("</" + name + ">");
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  int depth_ = 0;
};

class XdmfDocument final {
 public:
  XdmfDocument(const std::string& h5_file_name, const RunResult& result)
      : result_(result),
        h5_(xml_escape(h5_file_name)),
        nodes_(std::to_string(result.node_count())),
        bonds_(std::to_string(result.bond_count())),
        has_bonds_(result.bond_count() > 0) {}

  std::string text() {
    xml_.line(R"(<?xml version="1.0" encoding="utf-8"?>)");
    xml_.open("Xdmf", R"( xmlns:xi="http://www.w3.org/2001/XInclude" Version="3.0")");
    xml_.open("Domain");
    const std::string name = result_.scene.name.empty() ? "lattice" : result_.scene.name;
    if (result_.snapshots.empty()) {
      lattice(name, std::nullopt);
    } else {
      xml_.open("Grid", attr("Name", name) + R"( GridType="Collection" CollectionType="Temporal")");
      for (std::size_t i = 0; i < result_.snapshots.size(); ++i) {
        xml_.open("Grid", attr("Name", "snapshot " + std::to_string(i)) +
                              R"( GridType="Collection" CollectionType="Spatial")");
        xml_.line("<Time" + attr("Value", number_text(result_.snapshots[i].lambda)) + "/>");
        nodes_grid("/snapshots/" + std::to_string(i));
        if (has_bonds_) bonds_grid("/snapshots/" + std::to_string(i));
        xml_.close("Grid");
      }
      xml_.close("Grid");
    }
    xml_.close("Domain");
    xml_.close("Xdmf");
    return xml_.text();
  }

 private:
  void lattice(const std::string& name, const std::optional<std::string>& snapshot) {
    xml_.open("Grid", attr("Name", name) + R"( GridType="Collection" CollectionType="Spatial")");
    nodes_grid(snapshot);
    if (has_bonds_) bonds_grid(snapshot);
    xml_.close("Grid");
  }

  void data_item(const Dataset& dataset) {
    xml_.line("<DataItem Format=\"HDF\"" + attr("NumberType", dataset.number_type) +
              attr("Precision", std::to_string(dataset.precision)) +
              attr("Dimensions", dataset.dimensions) + ">" + h5_ + ":" + dataset.path +
              "</DataItem>");
  }

  void attribute(const std::string& name, const char* type, const char* center,
                 const Dataset& dataset) {
    xml_.open("Attribute",
              attr("Name", name) + attr("AttributeType", type) + attr("Center", center));
    data_item(dataset);
    xml_.close("Attribute");
  }

  void geometry() {
    xml_.open("Geometry", R"( GeometryType="XYZ")");
    data_item(float64("/lattice/positions", nodes_ + " 3"));
    xml_.close("Geometry");
  }

  // node_stress is Voigt-ordered (xx yy zz yz xz xy), not XDMF's Tensor6 order (xx xy xz
  // yy yz zz), so it is declared a 6-component Matrix and keeps its own component order.
  void nodes_grid(const std::optional<std::string>& snapshot) {
    xml_.open("Grid", R"( Name="nodes" GridType="Uniform")");
    xml_.open("Topology", R"( TopologyType="Polyvertex")" + attr("NumberOfElements", nodes_) +
                              R"( NodesPerElement="1")");
    data_item({"/lattice/node_index", nodes_, "Int", 8});
    xml_.close("Topology");
    geometry();
    if (snapshot) {
      attribute("displacement", "Vector", "Node",
                float64(*snapshot + "/displacement", nodes_ + " 3"));
      attribute("node_stress", "Matrix", "Node",
                float64(*snapshot + "/node_stress", nodes_ + " 6"));
    }
    xml_.close("Grid");
  }

  void bonds_grid(const std::optional<std::string>& snapshot) {
    xml_.open("Grid", R"( Name="bonds" GridType="Uniform")");
    xml_.open("Topology", R"( TopologyType="Polyline")" + attr("NumberOfElements", bonds_) +
                              R"( NodesPerElement="2")");
    data_item({"/lattice/bonds", bonds_ + " 2", "Int", 8});
    xml_.close("Topology");
    geometry();
    attribute("bond_kind", "Scalar", "Cell", {"/lattice/bond_kind", bonds_, "Char", 1});
    if (snapshot) {
      attribute("bond_intact", "Scalar", "Cell", {*snapshot + "/bond_intact", bonds_, "UChar", 1});
      attribute("bond_f", "Scalar", "Cell", float64(*snapshot + "/bond_f", bonds_));
      attribute("displacement", "Vector", "Node",
                float64(*snapshot + "/displacement", nodes_ + " 3"));
    }
    xml_.close("Grid");
  }

  const RunResult& result_;
  XmlLines xml_;
  std::string h5_;
  std::string nodes_;
  std::string bonds_;
  bool has_bonds_;
};

void write_text(const std::string& file_name, const std::string& text) {
  std::ofstream out(file_name, std::ios::binary | std::ios::trunc);
  if (!out) throw Error("cannot create '" + file_name + "': " + std::strerror(errno));
  out << text;
  out.close();
  if (!out) throw Error("cannot write '" + file_name + "': " + std::strerror(errno));
}

}  // namespace

void write_xdmf(const std::string& xmf_path, const std::string& h5_file_name,
                const RunResult& result) {
  const std::string text = XdmfDocument(h5_file_name, result).text();
  try {
    write_atomically(xmf_path, [&](const std::string& partial) { write_text(partial, text); });
  } catch (const Error& error) {
    throw Error("cannot write XDMF file '" + xmf_path + "': " + error.what());
  }
}

}  // namespace latfrac
