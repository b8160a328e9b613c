pub mod cylinders;
pub mod hertz_scene;
pub mod stress_cases;
