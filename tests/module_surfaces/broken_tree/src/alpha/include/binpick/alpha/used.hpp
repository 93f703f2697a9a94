#pragma once
// Included by module beta: public as it should be.
int used();
