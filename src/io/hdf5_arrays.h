// Typed, checked reads and writes of HDF5 datasets, attributes and groups by absolute path.
//
// Everything is addressed as (file, "/absolute/path") so every message can name the object.
// Writes throw latfrac::Error naming the failing HDF5 call. Reads throw InputError when
// the file lacks an object or holds one of the wrong shape (a file the user can replace)
// and Error when an HDF5 call fails on an object that is there.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace latfrac::hdf5 {

using Shape = std::vector<hsize_t>;

// The HDF5 types of a C++ element type: memory() as held here, file() as stored
// (fixed little-endian, so files are the same on every machine).
template <class T>
struct TypeOf;
template <>
struct TypeOf<double> {
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static hid_t file() { return H5T_IEEE_F64LE; }
};
template <>
struct TypeOf<std::int64_t> {
  static hid_t memory() { return H5T_NATIVE_INT64; }
  static hid_t file() { return H5T_STD_I64LE; }
};
template <>
struct TypeOf<std::uint64_t> {
  static hid_t memory() { return H5T_NATIVE_UINT64; }
  static hid_t file() { return H5T_STD_U64LE; }
};
template <>
struct TypeOf<std::int32_t> {
  static hid_t memory() { return H5T_NATIVE_INT32; }
  static hid_t file() { return H5T_STD_I32LE; }
};
template <>
struct TypeOf<std::int8_t> {
  static hid_t memory() { return H5T_NATIVE_INT8; }
  static hid_t file() { return H5T_STD_I8LE; }
};
template <>
struct TypeOf<std::uint8_t> {
  static hid_t memory() { return H5T_NATIVE_UINT8; }
  static hid_t file() { return H5T_STD_U8LE; }
};

hsize_t element_count(const Shape& shape);
std::string shape_text(const Shape& shape);  // "5 x 3"

void create_group(hid_t file, const std::string& path);
bool exists(hid_t file, const std::string& path);  // every component of path is a link
// True when the object at `object` has the attribute `name` (for attributes that older
// files lack).
bool has_attribute(hid_t file, const std::string& object, const char* name);
void require(hid_t file, const std::string& path, const char* what);  // InputError if absent
hsize_t link_count(hid_t file, const std::string& group_path);

void write_array(hid_t file, const std::string& path, hid_t file_type, hid_t memory_type,
                 const void* values, const Shape& shape);
Shape dataset_shape(hid_t file, const std::string& path);
void read_array(hid_t file, const std::string& path, hid_t memory_type, void* values,
                const Shape& expected_shape);

void write_attribute_value(hid_t file, const std::string& object, const char* name, hid_t file_type,
                           hid_t memory_type, const void* value);
void read_attribute_value(hid_t file, const std::string& object, const char* name,
                          hid_t memory_type, void* value);
void write_string_attribute(hid_t file, const std::string& object, const char* name,
                            const std::string& value);
std::string read_string_attribute(hid_t file, const std::string& object, const char* name);

template <class T>
void write_dataset(hid_t file, const std::string& path, const std::vector<T>& values,
                   const Shape& shape) {
  write_array(file, path, TypeOf<T>::file(), TypeOf<T>::memory(), values.data(), shape);
}

template <class T>
std::vector<T> read_dataset(hid_t file, const std::string& path, const Shape& expected_shape) {
  std::vector<T> values(element_count(expected_shape));
  read_array(file, path, TypeOf<T>::memory(), values.data(), expected_shape);
  return values;
}

template <class T>
void write_attribute(hid_t file, const std::string& object, const char* name, T value) {
  write_attribute_value(file, object, name, TypeOf<T>::file(), TypeOf<T>::memory(), &value);
}

template <class T>
T read_attribute(hid_t file, const std::string& object, const char* name) {
  T value{};
  read_attribute_value(file, object, name, TypeOf<T>::memory(), &value);
  return value;
}

}  // namespace latfrac::hdf5
