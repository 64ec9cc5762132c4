# Run by ctest as gltf.validator: the engine writes sample .glb and .gltf
# files and an animated .glb (export_gltf_sample), then the Khronos glTF
# Validator checks them.
# Inputs: SAMPLE (the program), NODE (node executable), TOOLS (this folder),
# OUT (a folder in the build tree). Nothing is downloaded here.
if(NOT EXISTS "${TOOLS}/node_modules/gltf-validator/package.json")
  message(FATAL_ERROR
    "gltf-validator is not installed: run `npm ci` in ${TOOLS} once "
    "(./run.sh build does it), then re-run the tests.")
endif()
if(NOT NODE OR NOT EXISTS "${NODE}")
  message(FATAL_ERROR "node (Node.js) was not found when configuring: install nodejs "
                      "and re-run cmake.")
endif()

file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND "${SAMPLE}" "${OUT}" RESULT_VARIABLE exported)
if(NOT exported EQUAL 0)
  message(FATAL_ERROR "export_gltf_sample failed (${exported})")
endif()
execute_process(
  COMMAND "${NODE}" "${TOOLS}/validate_gltf.js" "${OUT}/sample.glb" "${OUT}/sample.gltf"
          "${OUT}/sample_animation.glb"
  RESULT_VARIABLE validated)
if(NOT validated EQUAL 0)
  message(FATAL_ERROR "the glTF validator reported errors in ${OUT} (see above)")
endif()
