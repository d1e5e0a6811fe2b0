// bad.glsl: line 4 uses an undeclared name.
float bad()
{
    return undeclared_thing * 2.0;
}
