// Row j of a batch column: the column holds `count` values per row (an array member of an output
// struct, or one scalar); a NULL column is one the caller did not ask for, and nothing moves.
#pragma once

#include <cstddef>
#include <cstring>

namespace stewart {

template <typename T, size_t N>
void get_row(const T *column, size_t j, T (&value)[N]) {
    if (column) std::memcpy(value, column + j * N, sizeof value);
}
template <typename T, size_t N>
void put_row(T *column, size_t j, const T (&value)[N]) {
    if (column) std::memcpy(column + j * N, value, sizeof value);
}
template <typename T>
void put_row(T *column, size_t j, const T &value) {
    if (column) column[j] = value;
}

}  // namespace stewart
