# meshvid_target_defaults(TARGET): the include roots and warning flags every meshvid target uses.
# In the build tree, sources include each other by their path from the project root
# ("format/status.h") and the generated header as "meshvid/version.h". Installed, the headers
# live under <prefix>/include/meshvid/ (users write <meshvid/codec/dec/mvid_decoder.h>), and
# include/meshvid is on the include path too so the headers' own includes resolve.
function(meshvid_target_defaults target)
  get_target_property(type ${target} TYPE)
  set(roots $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
            $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
            $<INSTALL_INTERFACE:include> $<INSTALL_INTERFACE:include/meshvid>)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE ${roots})
  else()
    target_include_directories(${target} PUBLIC ${roots})
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
  endif()
endfunction()
