#pragma once
// Included by no other module: the check must name it.
int unused();
