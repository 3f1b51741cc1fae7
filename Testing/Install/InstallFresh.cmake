# cmake -D BUILD_DIR=<build> -D PREFIX=<prefix> -P InstallFresh.cmake
# Installs the build into an emptied prefix, so that files left by an earlier install cannot hide
# one this install misses.
file(REMOVE_RECURSE "${PREFIX}")
execute_process(
  COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
  OUTPUT_QUIET
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed: ${result}")
endif ()
foreach (file IN ITEMS lib/cmake/vtkSAVR/vtkSAVRConfig.cmake include/vtkSAVR/vtkSAVRVolumeMapper.h
    include/vtkSAVR/savr/sampler/Sampler.h)
  if (NOT EXISTS "${PREFIX}/${file}")
    message(FATAL_ERROR "the install holds no ${file}")
  endif ()
endforeach ()
