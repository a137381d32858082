# engine_add_plugin(<name> SOURCES ... [SHARED]): a plugin library linked against the engine.
# Static plugins register through engine::PluginManager::add_static(); shared ones export
# the C entry points declared in engine/plugin/plugin_abi.h and are loaded with dlopen.
function(engine_add_plugin name)
  cmake_parse_arguments(ARG "SHARED" "" "SOURCES" ${ARGN})
  if(ARG_SHARED)
    add_library(${name} MODULE ${ARG_SOURCES})
    set_target_properties(${name} PROPERTIES PREFIX "" CXX_VISIBILITY_PRESET hidden)
  else()
    add_library(${name} STATIC ${ARG_SOURCES})
  endif()
  target_link_libraries(${name} PUBLIC engine)
  engine_set_warnings(${name})
endfunction()
