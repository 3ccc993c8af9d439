# The scene layer's loader and validation sources, shared by the fetic_scenes library and
# the fuzz target (fuzz/CMakeLists.txt), so that a new scene source cannot be forgotten in
# one of them. Paths are relative to this folder.
set(FETIC_SCENE_LOADER_SOURCES
  scene.cpp
  scene_error.cpp
  scene_geometry.cpp
  load_scene.cpp
  scene_text.cpp
  toml_guard.cpp
  units.cpp
  validate_scene.cpp
  validate_frame.cpp
  frame_kinematics.cpp
  null_space.cpp
  sparse_null_space.cpp
  magnitudes.cpp
  write_scene.cpp)
