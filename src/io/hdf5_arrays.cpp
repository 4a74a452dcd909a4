// Typed, checked reads and writes of HDF5 datasets, attributes and groups by absolute path.
#include "hdf5_arrays.h"

#include <algorithm>
#include <cstddef>
#include <string>

#include "hdf5_handles.h"
#include "latfrac/base/error.h"

namespace latfrac::hdf5 {

namespace {

std::string attribute_label(const std::string& object, const char* name) {
  return "attribute '" + std::string(name) + "' of " + object;
}

Handle open_dataset(hid_t file, const std::string& path) {
  require(file, path, "dataset");
  return checked(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose, "H5Dopen2", path);
}

Handle open_attribute(hid_t file, const std::string& object, const char* name) {
  const std::string label = attribute_label(object, name);
  require(file, object, "group");
  const htri_t found = H5Aexists_by_name(file, object.c_str(), name, H5P_DEFAULT);
  if (found < 0) fail("H5Aexists_by_name", label);
  if (found == 0) throw InputError(label + " is missing");
  return checked(H5Aopen_by_name(file, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                 "H5Aopen_by_name", label);
}

void require_number_type(hid_t stored_type, const std::string& label) {
  const H5T_class_t type_class = H5Tget_class(stored_type);
  if (type_class < 0) fail("H5Tget_class", label);
  if (type_class != H5T_INTEGER && type_class != H5T_FLOAT) {
    throw InputError(label + " does not hold numbers");
  }
  // HDF5 converts whatever width the file names; a damaged width (a flipped byte made one
  // 524289 bytes) made H5Dread run off its buffers instead of failing.
  const std::size_t size = H5Tget_size(stored_type);
  if (size == 0) fail("H5Tget_size", label);
  const bool usual = type_class == H5T_FLOAT ? (size == 4 || size == 8)
                                             : (size == 1 || size == 2 || size == 4 || size == 8);
  if (!usual)
    throw InputError(label + " holds numbers of " + std::to_string(size) +
                     " bytes, which latfrac never writes: the file is damaged");
}

Shape extent(hid_t space, const std::string& label) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail("H5Sget_simple_extent_ndims", label);
  Shape shape(static_cast<std::size_t>(rank));
  if (H5Sget_simple_extent_dims(space, shape.data(), nullptr) < 0) {
    fail("H5Sget_simple_extent_dims", label);
  }
  return shape;
}

}  // namespace

hsize_t element_count(const Shape& shape) {
  hsize_t count = 1;
  for (hsize_t extent : shape) count *= extent;
  return count;
}

std::string shape_text(const Shape& shape) {
  if (shape.empty()) return "scalar";
  std::string text;
  for (hsize_t extent : shape) text += (text.empty() ? "" : " x ") + std::to_string(extent);
  return text;
}

void create_group(hid_t file, const std::string& path) {
  checked(H5Gcreate2(file, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
          "H5Gcreate2", path)
      .close("H5Gclose", path);
}

bool has_attribute(hid_t file, const std::string& object, const char* name) {
  const htri_t found = H5Aexists_by_name(file, object.c_str(), name, H5P_DEFAULT);
  if (found < 0) fail("H5Aexists_by_name", attribute_label(object, name));
  return found > 0;
}

bool exists(hid_t file, const std::string& path) {
  for (std::size_t end = path.find('/', 1);; end = path.find('/', end + 1)) {
    const std::string prefix = path.substr(0, end);
    const htri_t found = H5Lexists(file, prefix.c_str(), H5P_DEFAULT);
    if (found < 0) fail("H5Lexists", prefix);
    if (found == 0) return false;
    if (end == std::string::npos) return true;
  }
}

void require(hid_t file, const std::string& path, const char* what) {
  if (!exists(file, path)) throw InputError(std::string(what) + " " + path + " is missing");
}

hsize_t link_count(hid_t file, const std::string& group_path) {
  require(file, group_path, "group");
  H5G_info_t info;
  check(H5Gget_info_by_name(file, group_path.c_str(), &info, H5P_DEFAULT), "H5Gget_info_by_name",
        group_path);
  return info.nlinks;
}

// A non-empty array is stored in chunks of at most about 1 MiB, each with a Fletcher-32
// checksum that HDF5 verifies on every read: a damaged file (a flipped byte that still
// reads as a finite number) fails to read instead of giving absurd values. An empty
// array is contiguous (a chunk cannot be empty). The arrays are written once and read whole.
void write_array(hid_t file, const std::string& path, hid_t file_type, hid_t memory_type,
                 const void* values, const Shape& shape) {
  Handle space = checked(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr),
                         H5Sclose, "H5Screate_simple", path);
  Handle layout = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate", path);
  if (element_count(shape) > 0) {
    Shape chunk = shape;
    const hsize_t row_bytes = element_count(shape) / shape[0] * H5Tget_size(file_type);
    chunk[0] =
        std::clamp<hsize_t>((hsize_t{1} << 20) / std::max<hsize_t>(row_bytes, 1), 1, shape[0]);
    check(H5Pset_chunk(layout.get(), static_cast<int>(chunk.size()), chunk.data()), "H5Pset_chunk",
          path);
    check(H5Pset_fletcher32(layout.get()), "H5Pset_fletcher32", path);
  }
  Handle dataset = checked(H5Dcreate2(file, path.c_str(), file_type, space.get(), H5P_DEFAULT,
                                      layout.get(), H5P_DEFAULT),
                           H5Dclose, "H5Dcreate2", path);
  if (element_count(shape) > 0) {
    check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values), "H5Dwrite",
          path);
  }
  dataset.close("H5Dclose", path);
}

Shape dataset_shape(hid_t file, const std::string& path) {
  Handle dataset = open_dataset(file, path);
  Handle space = checked(H5Dget_space(dataset.get()), H5Sclose, "H5Dget_space", path);
  return extent(space.get(), path);
}

void read_array(hid_t file, const std::string& path, hid_t memory_type, void* values,
                const Shape& expected_shape) {
  Handle dataset = open_dataset(file, path);
  Handle space = checked(H5Dget_space(dataset.get()), H5Sclose, "H5Dget_space", path);
  const Shape shape = extent(space.get(), path);
  if (shape != expected_shape) {
    throw InputError("dataset " + path + " is " + shape_text(shape) + ", expected " +
                     shape_text(expected_shape));
  }
  Handle stored_type = checked(H5Dget_type(dataset.get()), H5Tclose, "H5Dget_type", path);
  require_number_type(stored_type.get(), "dataset " + path);
  if (element_count(shape) > 0) {
    // A checksum that does not match fails here: say what that means.
    if (H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) < 0)
      throw InputError("dataset " + path +
                       " cannot be read (H5Dread failed; a stored checksum that does not match "
                       "means the file is damaged)");
  }
}

void write_attribute_value(hid_t file, const std::string& object, const char* name, hid_t file_type,
                           hid_t memory_type, const void* value) {
  const std::string label = attribute_label(object, name);
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", label);
  Handle attribute = checked(H5Acreate_by_name(file, object.c_str(), name, file_type, space.get(),
                                               H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             H5Aclose, "H5Acreate_by_name", label);
  check(H5Awrite(attribute.get(), memory_type, value), "H5Awrite", label);
  attribute.close("H5Aclose", label);
}

void read_attribute_value(hid_t file, const std::string& object, const char* name,
                          hid_t memory_type, void* value) {
  const std::string label = attribute_label(object, name);
  Handle attribute = open_attribute(file, object, name);
  Handle space = checked(H5Aget_space(attribute.get()), H5Sclose, "H5Aget_space", label);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) {
    throw InputError(label + " is not a single value");
  }
  Handle stored_type = checked(H5Aget_type(attribute.get()), H5Tclose, "H5Aget_type", label);
  require_number_type(stored_type.get(), label);
  check(H5Aread(attribute.get(), memory_type, value), "H5Aread", label);
}

// Variable-length UTF-8: no size limit from the attribute's header message, and h5py
// reads it back as str.
void write_string_attribute(hid_t file, const std::string& object, const char* name,
                            const std::string& value) {
  const std::string label = attribute_label(object, name);
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy", label);
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size", label);
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", label);
  const char* text = value.c_str();
  write_attribute_value(file, object, name, type.get(), type.get(), &text);
}

std::string read_string_attribute(hid_t file, const std::string& object, const char* name) {
  const std::string label = attribute_label(object, name);
  Handle attribute = open_attribute(file, object, name);
  Handle stored_type = checked(H5Aget_type(attribute.get()), H5Tclose, "H5Aget_type", label);
  if (H5Tget_class(stored_type.get()) != H5T_STRING) {
    throw InputError(label + " is not a string");
  }
  const htri_t variable = H5Tis_variable_str(stored_type.get());
  if (variable < 0) fail("H5Tis_variable_str", label);
  Handle memory_type = checked(H5Tcopy(stored_type.get()), H5Tclose, "H5Tcopy", label);
  check(H5Tset_strpad(memory_type.get(), H5T_STR_NULLTERM), "H5Tset_strpad", label);
  if (variable > 0) {
    char* text = nullptr;
    check(H5Aread(attribute.get(), memory_type.get(), &text), "H5Aread", label);
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(stored_type.get());
  if (size == 0) fail("H5Tget_size", label);
  if (size > (std::size_t{1} << 20))
    throw InputError(label + " is a string of " + std::to_string(size) +
                     " bytes, which latfrac never writes: the file is damaged");
  std::string buffer(size + 1, '\0');
  check(H5Tset_size(memory_type.get(), size + 1), "H5Tset_size", label);
  check(H5Aread(attribute.get(), memory_type.get(), buffer.data()), "H5Aread", label);
  return buffer.substr(0, buffer.find('\0'));
}

}  // namespace latfrac::hdf5
