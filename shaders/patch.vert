#version 400 core
// GPU tessellation of Bezier patches: the control points pass through untouched (as
// mass-points: (w P, w), so rational patches are evaluated exactly).
in vec4 in_control;
out vec4 c_control;

void main() {
    c_control = in_control;
}
