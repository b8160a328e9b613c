pub mod hertz_scene;
