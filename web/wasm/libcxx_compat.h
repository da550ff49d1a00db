// Included before every source of the WebAssembly build: the C++20 library parts meshvid uses
// that Emscripten's libc++ (Debian's 3.1.6) lacks.
#ifndef MESHVID_WEB_WASM_LIBCXX_COMPAT_H_
#define MESHVID_WEB_WASM_LIBCXX_COMPAT_H_

#include <bit>
#include <version>

#if !defined(__cpp_lib_bit_cast)
#include <cstring>
#include <type_traits>

namespace std {
/// std::bit_cast (C++20) for trivially copyable types of one size, as the standard defines it.
template <class To, class From>
To bit_cast(const From& from) noexcept {
  static_assert(sizeof(To) == sizeof(From) && is_trivially_copyable_v<To> &&
                is_trivially_copyable_v<From>);
  To to;
  memcpy(&to, &from, sizeof(To));
  return to;
}
}  // namespace std
#endif

#endif  // MESHVID_WEB_WASM_LIBCXX_COMPAT_H_
