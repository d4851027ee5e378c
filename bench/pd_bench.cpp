// placeholder, replaced by the bench helper
int main() { return 0; }
