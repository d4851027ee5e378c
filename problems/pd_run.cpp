// placeholder, replaced by the pd_run helper
int main() { return 0; }
